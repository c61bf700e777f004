#!/usr/bin/env bash
# The study scripts check their arguments before they run anything: each bad call below must exit 2 with a message
# on standard error, within 60 s, with no Python traceback, and create no output folder. CTest runs it (label
# "app") with the driver's path: tests/scripts/test_script_arguments.sh BLASTSIM REPOSITORY
set -uo pipefail
blastsim=$(readlink -f "$1")
repo=$(readlink -f "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
touch a_file
mkdir a_folder
case_file=$repo/examples/single_hole/single_hole.toml
failures=0 calls=0
# expect NAME COMMAND...: exit 2, a message, no traceback, no folder "out" made.
expect() {
  local name=$1 rc
  shift
  calls=$((calls + 1))
  timeout 60 "$@" > stdout.txt 2> stderr.txt
  rc=$?
  if [ "$rc" -ne 2 ] || [ ! -s stderr.txt ] || grep -q "Traceback" stderr.txt stdout.txt || [ -e out ]; then
    echo "FAIL $name: exit $rc (expected 2), stderr: $(head -c 400 stderr.txt)"
    failures=$((failures + 1))
  else
    echo "ok   $name: $(tail -n 1 stderr.txt | head -c 160)"
  fi
  rm -rf out
}
py=/usr/bin/python3
[ -x "$py" ] || py=python3
realisations=("$py" "$repo/scripts/realisations.py")
expect "realisations: a malformed override" "${realisations[@]}" "$case_file" 2 --out out --blastsim "$blastsim" time.end=abc
expect "realisations: an override without =" "${realisations[@]}" "$case_file" 2 --out out --blastsim "$blastsim" time.end
expect "realisations: an output path that is a file" "${realisations[@]}" "$case_file" 2 --out a_file --blastsim "$blastsim"
expect "realisations: a driver path that is a folder" "${realisations[@]}" "$case_file" 2 --out out --blastsim a_folder
expect "realisations: no such case" "${realisations[@]}" no_such.toml 2 --out out --blastsim "$blastsim"
expect "realisations: N = 0" "${realisations[@]}" "$case_file" 0 --out out --blastsim "$blastsim"
expect "realisations: N not a number" "${realisations[@]}" "$case_file" x --out out --blastsim "$blastsim"
expect "realisations: a jitter the driver refuses" "${realisations[@]}" "$case_file" 2 --out out --blastsim "$blastsim" --jitter -1
expect "realisations: --jobs 0" "${realisations[@]}" "$case_file" 2 --out out --blastsim "$blastsim" --jobs 0
expect "realisations: --collect-only without runs" "${realisations[@]}" "$case_file" 2 --out a_folder --collect-only
expect "check-idiom: a root that is no blastsim tree" "$py" "$repo/scripts/check-idiom.py" --root a_folder
# The shell studies look for the driver in the repository's build-cpu; give them this build's through a link.
mkdir -p repo/scripts repo/examples/single_hole repo/build-cpu/apps/blastsim
cp "$repo/scripts/refine-single-hole.sh" "$repo/scripts/stress-blast-study.sh" "$repo/scripts/cpu-scaling.sh" repo/scripts/
cp "$case_file" repo/examples/single_hole/
ln -s "$blastsim" repo/build-cpu/apps/blastsim/blastsim
for level in abc -5:0.03 "" 280:x 1e3:0.03 9999999:0.03; do
  expect "refine-single-hole: level '$level'" bash repo/scripts/refine-single-hole.sh out "$level"
done
expect "refine-single-hole: an output root that is a file" bash repo/scripts/refine-single-hole.sh a_file 280:0.03
expect "refine-single-hole: a level the driver refuses" bash repo/scripts/refine-single-hole.sh out 20:0.0000001
expect "stress-blast-study: an output path that is a file" bash repo/scripts/stress-blast-study.sh a_file
expect "stress-blast-study: two folders" bash repo/scripts/stress-blast-study.sh out other
for max in 0 x 99999999999999999999 2000; do
  expect "cpu-scaling: MAX_THREADS $max" bash repo/scripts/cpu-scaling.sh "$max"
done
expect "cpu-scaling: REPEATS 9999999" env REPEATS=9999999 bash repo/scripts/cpu-scaling.sh 2
expect "cpu-scaling: SECONDS 10" bash repo/scripts/cpu-scaling.sh 2 10
echo "script arguments: $((calls - failures)) of $calls bad calls refused with exit 2 and a message, no traceback"
[ "$failures" -eq 0 ]
