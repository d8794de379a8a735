#!/usr/bin/env bash
# Downloads the public BVH clips of the reduce comparison into DIR (default
# $CARGO_TARGET_DIR/reduce-compare/clips, else target/reduce-compare/clips). Never committed.
#
# - Debian package assimp-testmodels (apt-get download, unpacked with dpkg -x):
#   /usr/share/assimp/models/BVH/01_01.bvh, 01_03.bvh (CMU Graphics Lab motion capture, cgspeed BVH
#   conversion, 120 fps; free for any use) and Boxing_Toes.bvh (100 fps).
# - PyPI sdists (pip download --no-deps --no-binary :all:): bvhtools 1.6.0 testBvhFiles/test.bvh,
#   test2.bvh (30 fps), test3.bvh (24 fps); bvhtoolbox 0.1.3 tests/example_files/test_mocapbank.bvh,
#   test_freebvh.bvh (30 fps).
# Usage: fetch_clips.sh [DIR] [PIP]   (PIP: the pip to download with; default pip3)
set -euo pipefail
root="$(cd "$(dirname "$0")/../../.." && pwd)"
dir="${1:-${CARGO_TARGET_DIR:-$root/target}/reduce-compare/clips}"
pip="${2:-pip3}"
want=(01_01.bvh 01_03.bvh Boxing_Toes.bvh test.bvh test2.bvh test3.bvh test_mocapbank.bvh test_freebvh.bvh)
mkdir -p "$dir"
have=1
for f in "${want[@]}"; do [ -s "$dir/$f" ] || have=0; done
[ "$have" = 1 ] && exit 0
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
(cd "$tmp" && apt-get download assimp-testmodels >/dev/null)
dpkg -x "$tmp"/assimp-testmodels_*.deb "$tmp/deb"
for f in 01_01.bvh 01_03.bvh Boxing_Toes.bvh 01_nn.bvh.source.txt; do
  cp "$tmp/deb/usr/share/assimp/models/BVH/$f" "$dir/"
done
"$pip" download -q --no-deps --no-binary :all: -d "$tmp/sdist" bvhtools==1.6.0 bvhtoolbox==0.1.3
tar -xzf "$tmp"/sdist/bvhtools-1.6.0.tar.gz -C "$tmp"
tar -xzf "$tmp"/sdist/bvhtoolbox-0.1.3.tar.gz -C "$tmp"
cp "$tmp"/bvhtools-1.6.0/testBvhFiles/{test,test2,test3}.bvh "$dir/"
cp "$tmp"/bvhtoolbox-0.1.3/tests/example_files/{test_mocapbank,test_freebvh}.bvh "$dir/"
(cd "$dir" && apt-cache show assimp-testmodels 2>/dev/null | grep -m1 '^Version' > SOURCES.txt || true;
 echo "bvhtools==1.6.0 bvhtoolbox==0.1.3 (PyPI sdists)" >> SOURCES.txt)
ls -l "$dir"
