#!/usr/bin/env bash
# The rawlog-grabber plugin (libsemnav_hwdrivers.so) links no simulator,
# emulator or training code: neither the plugin nor the hwdrivers library it
# is made of defines or references their classes, and the plugin loads no
# semnav library beside itself.
# Usage: plugin_links_no_simulator.sh libsemnav_hwdrivers.so libsemnav_hwdrivers.a
set -euo pipefail
usage="usage: $0 libsemnav_hwdrivers.so libsemnav_hwdrivers.a"
plugin=${1:?$usage}
library=${2:?$usage}
for f in "$plugin" "$library"; do
  [[ -f $f ]] || { echo "plugin_links_no_simulator: no file $f" >&2; exit 1; }
done

defined=$(nm -C --defined-only "$plugin")
if ! grep -q 'semnav::CTiltingLMS2xx' <<<"$defined"; then
  echo "plugin_links_no_simulator: $plugin defines no semnav::CTiltingLMS2xx (wrong file?)" >&2
  exit 1
fi
forbidden='semnav::(RayCaster|Scene|SceneLoader|OdometrySimulator|SimulationRunner|TiltingLaserSimulator|SceneLineCaster|LmsEmulator|PtuEmulator|TiltingScannerEmulator|PseudoTerminal|CaptureCheck|SampleGenerator|CascadeTraining|ShapeTraining|ObjectScorer|SimDataset|GroundTruthObject)\b'
for f in "$plugin" "$library"; do
  symbols=$(nm -C "$f" 2>/dev/null)
  found=$(grep -E "$forbidden" <<<"$symbols" | head -5 || true)
  if [[ -n $found ]]; then
    echo "plugin_links_no_simulator: $f defines or references simulation code:" >&2
    echo "$found" >&2
    exit 1
  fi
done
if ldd "$plugin" | grep -E 'libsemnav_'; then
  echo "plugin_links_no_simulator: $plugin loads another semnav library" >&2
  exit 1
fi
echo "plugin_links_no_simulator: $(grep -c 'semnav::' <<<"$defined") semnav symbols" \
  "in $(basename "$plugin"), none from sim, emulation or training (nor in $(basename "$library"))"
