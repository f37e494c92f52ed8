#!/usr/bin/env bash
# A test that runs the runtime against fakes links no simulator, emulator or
# training code: its sources include nothing from semnav/sim, navsim,
# emulation or training, and its binary neither defines nor references
# their classes.
# Usage: test_links_no_simulator.sh <test binary> <its source directory>
set -euo pipefail
usage="usage: $0 <test binary> <source directory>"
binary=${1:?$usage}
sources=${2:?$usage}
[[ -f $binary ]] || { echo "test_links_no_simulator: no file $binary" >&2; exit 1; }
[[ -d $sources ]] || { echo "test_links_no_simulator: no directory $sources" >&2; exit 1; }

if grep -nE '#\s*include\s*[<"]semnav/(sim|navsim|emulation|training)/' \
    "$sources"/*.h "$sources"/*.cpp >&2; then
  echo "test_links_no_simulator: $sources includes simulation code" >&2
  exit 1
fi
symbols=$(nm -C "$binary")
if ! grep -q 'semnav::StopAndScanLocalizer::start' <<<"$symbols"; then
  echo "test_links_no_simulator: $binary has no semnav::StopAndScanLocalizer (wrong file?)" >&2
  exit 1
fi
forbidden='semnav::(Simulated[A-Za-z]*|SimulationRunner|SimulationConfig|RayCaster|RayCastObstacles|Scene|SceneLoader|SceneMapBuilder|OdometrySimulator|TiltingLaserSimulator|SceneLineCaster|LmsEmulator|PtuEmulator|TiltingScannerEmulator|PseudoTerminal|SampleGenerator|CascadeTraining|ShapeTraining|ObjectScorer|SimDataset|GroundTruthObject)\b'
found=$(grep -E "$forbidden" <<<"$symbols" | head -5 || true)
if [[ -n $found ]]; then
  echo "test_links_no_simulator: $binary defines or references simulation code:" >&2
  echo "$found" >&2
  exit 1
fi
echo "test_links_no_simulator: $(basename "$binary") links no sim, navsim, emulation or training code"
