#!/usr/bin/env bash
# Installs the npm packages that tests use to read motifmine's outputs with readers the project
# did not write, into BUILD_DIR/npm (never into the source tree): three.js, whose BVHLoader
# reads walk.bvh in tests/engine/graph/two_styles_test.cc. Needs the machine's Node.js and npm;
# without them, or offline, it warns and the tests that need the packages skip with a message.
#
#   scripts/install_npm_test_deps.sh BUILD_DIR
set -euo pipefail
prefix="$1/npm"
three_version=0.170.0
if [ -f "$prefix/node_modules/three/package.json" ] &&
   grep -q "\"version\": \"$three_version\"" "$prefix/node_modules/three/package.json"; then
  exit 0
fi
if ! command -v npm >/dev/null 2>&1; then
  echo "warning: no npm: the tests that read BVH with three.js will skip" >&2
  exit 0
fi
mkdir -p "$prefix"
if ! npm install --prefix "$prefix" --no-audit --no-fund --silent "three@$three_version" >&2; then
  echo "warning: npm install three@$three_version failed: the tests that read BVH with three.js will skip" >&2
fi
