# Helpers for registering tests that can fail.

option(PROXYGI_ALLOW_MISSING_TESTS
  "Warn only (no failing placeholder) where a test cannot be registered" OFF)

# The wrapper that judges a test by its exit code and its output together.
set(PROXYGI_RUN_CHECKED "${CMAKE_CURRENT_LIST_DIR}/../Testing/run_checked.sh")
get_filename_component(PROXYGI_RUN_CHECKED "${PROXYGI_RUN_CHECKED}" ABSOLUTE)

# A test that cannot be registered here (a tool, a library or a target is
# missing) says so at configure time and, unless PROXYGI_ALLOW_MISSING_TESTS
# is on, stands in the run as a failing test with the reason.
function (proxygi_test_unavailable name reason)
  message(WARNING "ProxyGI: test ${name} not registered: ${reason}")
  if (NOT PROXYGI_ALLOW_MISSING_TESTS)
    add_test(NAME "${name}"
      COMMAND "${CMAKE_COMMAND}" -E echo "not registered: ${reason}")
    set_tests_properties("${name}" PROPERTIES LABELS "ProxyGI"
      FAIL_REGULAR_EXPRESSION "not registered")
  endif ()
endfunction ()

# Whether the set-up script's data (meshes, HDR maps) is there.
set(PROXYGI_HAVE_DATA OFF)
if (EXISTS "${PROXYGI_DATA_DIR}/meshes/bunny00.off" AND
    EXISTS "${PROXYGI_DATA_DIR}/environments/forest.exr")
  set(PROXYGI_HAVE_DATA ON)
endif ()


# add_test through run_checked.sh: the test passes only with the exit code
# it expects AND the output it expects.
#   proxygi_add_checked_test(NAME
#     [EXIT 0|N|refused] [PASS regex...] [FAIL regex...] [LAST regex]
#     [LABELS label...] COMMAND command args...)
# FAIL always includes a non-finite number printed as a result.
function (proxygi_add_checked_test name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "EXIT;LAST;WORKING_DIRECTORY" "PASS;FAIL;LABELS;COMMAND")
  if (NOT arg_COMMAND)
    message(FATAL_ERROR "proxygi_add_checked_test(${name}): no COMMAND")
  endif ()
  set(checks --exit "0")
  if (DEFINED arg_EXIT)
    set(checks --exit "${arg_EXIT}")
  endif ()
  foreach (re IN LISTS arg_PASS)
    list(APPEND checks --pass "${re}")
  endforeach ()
  foreach (re IN LISTS arg_FAIL ITEMS "(^|[ =(])[-+]?(nan|inf)(%| |$)")
    list(APPEND checks --fail "${re}")
  endforeach ()
  if (DEFINED arg_LAST)
    list(APPEND checks --last "${arg_LAST}")
  endif ()
  set(where)
  if (arg_WORKING_DIRECTORY)
    set(where WORKING_DIRECTORY "${arg_WORKING_DIRECTORY}")
  endif ()
  add_test(NAME "${name}" COMMAND "${PROXYGI_RUN_CHECKED}" ${checks} -- ${arg_COMMAND} ${where})
  set(labels "ProxyGI")
  if (arg_LABELS)
    set(labels ${arg_LABELS})
  endif ()
  set_tests_properties("${name}" PROPERTIES LABELS "${labels}")
endfunction ()
