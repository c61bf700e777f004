#!/usr/bin/env bash
# scripts/check-idiom.py passes on this tree, and on its fixture (tests/scripts/idiom_fixture: one violation of
# each rule) it exits 1 naming every rule: a check that could not fail would pass the tree for nothing.
# Usage: tests/scripts/test_check_idiom.sh REPOSITORY
set -uo pipefail
repo=$(readlink -f "$1")
py=/usr/bin/python3
[ -x "$py" ] || py=python3
"$py" "$repo/scripts/check-idiom.py" --root "$repo" || { echo "FAIL: the tree breaks the idiom"; exit 1; }
out=$("$py" "$repo/scripts/check-idiom.py" --root "$repo/tests/scripts/idiom_fixture" 2>&1)
rc=$?
echo "$out"
[ "$rc" -eq 1 ] || { echo "FAIL: the fixture gave exit $rc, expected 1"; exit 1; }
for rule in thrust lambda functor pointer array; do
  grep -q ": $rule: " <<< "$out" || { echo "FAIL: the fixture's $rule violation was not found"; exit 1; }
done
echo "check-idiom: the tree passes; the fixture's five kinds of violation are all found"
