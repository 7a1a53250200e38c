#!/bin/bash
# The ParaView GUI client under Xvfb with the ProxyGI plugin: plays
# gui_client.xml (menus, representation toolbar, properties panel) and
# grabs the screen while it runs (the last steady frame is kept as
# WORKDIR/gui-client.png, the picture in Documentation/ParaView.md).
#   gui_client.sh PARAVIEW PLUGIN_DIR MESH WORKDIR   (run by run_under_xvfb.sh)
set -u
paraview=$1 plugin_dir=$2 mesh=$3 work=$4
here="$(cd "$(dirname "$0")" && pwd)"
rm -rf "$work" && mkdir -p "$work/config/ParaView" "$work/frames"
# A fresh user configuration: no welcome dialog (it is modal), no history.
printf '[General]\nGeneralSettings.ShowWelcomeDialog=false\n' \
  > "$work/config/ParaView/ParaView5.11.0.ini"
XDG_CONFIG_HOME="$work/config" "$paraview" \
  --plugin-search-paths="$plugin_dir" --plugins=ProxyGI --data="$mesh" \
  --test-script="$here/gui_client.xml" --test-directory="$work" --exit &
pid=$!
k=0
while kill -0 "$pid" 2>/dev/null; do
  sleep 1
  k=$((k + 1))
  /usr/bin/python3 -c "import sys; from PIL import ImageGrab; ImageGrab.grab(xdisplay=sys.argv[2]).save(sys.argv[1])" \
    "$work/frames/$(printf %03d $k).png" "$DISPLAY" 2>/dev/null || true
done
wait "$pid"
status=$?
# The frame two seconds before the end: the last playback step is a pause.
frame=$(ls "$work/frames" | sort | tail -n 3 | head -n 1)
[ -n "$frame" ] && cp "$work/frames/$frame" "$work/gui-client.png"
echo "paraview exit status $status"
exit $status
