#!/bin/sh
# Runs the sample scene generator twice into OUT/a and OUT/b and checks that the outputs are
# byte-identical (deterministic generator). Usage: generate_twice.sh GENERATOR OUT
set -eu
gen=$1
out=$2
rm -rf "$out"
mkdir -p "$out"
"$gen" -q "$out/a"
"$gen" -q "$out/b"
diff -r "$out/a" "$out/b"
n=$(find "$out/a/textures" -type f | wc -l)
echo "generated $n textures; two runs identical"
test "$n" -ge 40
# no temporary files left behind
test -z "$(find "$out" -name '.*' -type f)"
