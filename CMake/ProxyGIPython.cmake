# The Python package proxygi: every module wrapped with VTK's Python wrapper
# (proxygi.ProxyGIShading, ...), an __init__.py that imports them all, built
# under ${PROXYGI_PYTHON_DIR} (add it to PYTHONPATH) and installed with the
# platform's Python modules.
set(PROXYGI_PYTHON_DESTINATION
  "${CMAKE_INSTALL_LIBDIR}/python${Python3_VERSION_MAJOR}/dist-packages")
set(PROXYGI_PYTHON_DIR "${CMAKE_BINARY_DIR}/${PROXYGI_PYTHON_DESTINATION}")
vtk_module_wrap_python(
  MODULES            ${proxygi_python_modules_to_wrap}
  TARGET             ProxyGI::Python
  WRAPPED_MODULES    proxygi_python_wrapped
  PYTHON_PACKAGE     "proxygi"
  MODULE_DESTINATION "${PROXYGI_PYTHON_DESTINATION}"
  CMAKE_DESTINATION  "${CMAKE_INSTALL_LIBDIR}/cmake/proxygi"
  LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  INSTALL_EXPORT     ProxyGIPython
  INSTALL_HEADERS    OFF
  BUILD_STATIC       OFF)

set(proxygi_python_imports "")
foreach (module IN LISTS proxygi_python_wrapped)
  get_property(library TARGET "${module}" PROPERTY "INTERFACE_vtk_module_library_name")
  string(APPEND proxygi_python_imports "from .${library} import *\n")
endforeach ()
file(GENERATE
  OUTPUT  "${PROXYGI_PYTHON_DIR}/proxygi/__init__.py"
  CONTENT "\"\"\"ProxyGI: sphere proxies and SH global illumination for VTK.\"\"\"\n\n${proxygi_python_imports}")
install(FILES "${PROXYGI_PYTHON_DIR}/proxygi/__init__.py"
  DESTINATION "${PROXYGI_PYTHON_DESTINATION}/proxygi")
