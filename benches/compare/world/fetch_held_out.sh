#!/usr/bin/env bash
# Downloads the held-out clips of the world-space comparison into DIR (default
# $CARGO_TARGET_DIR/world-compare/held-out, else target/world-compare/held-out). Never committed.
# Real motion capture held out from the world rule's design (docs/reduce.md, "World space"; the
# k^0.7 start of f4f3a67 was compared on it too, so a fresh set is needed for a clean test):
#
# - mass_*.bvh: the eight clips of lsw9021/MASS, data/motion/ (commit e44c2ef, Apache-2.0;
#   CMU-derived capture, 120 fps, 37 joints, centimetres).
# - xia_*.bvh: the ten clips of DeepMotionEditing/deep-motion-editing, style_transfer/data/xia_test/
#   and blender_rendering/example.bvh (commit 74fff8f; from Xia et al. 2015's style capture on the
#   CMU skeleton, 120 fps, 31 joints; one unit 5.6444 cm as for the CMU clips).
#
# Each file is checked against the SHA-256 below. Usage: fetch_held_out.sh [DIR]
set -euo pipefail
root="$(cd "$(dirname "$0")/../../.." && pwd)"
dir="${1:-${CARGO_TARGET_DIR:-$root/target}/world-compare/held-out}"
mass=https://raw.githubusercontent.com/lsw9021/MASS/e44c2ef184cb55d45afd16b000414c84092ae18e
dme=https://raw.githubusercontent.com/DeepMotionEditing/deep-motion-editing/74fff8fb35e6378351d03fb14ee22fccae28b0bf
files="
26781e6b17183d0701431bb5c03e18af32ad937aef555f39f6b8d501b4ac805c mass_backflip.bvh $mass/data/motion/backflip.bvh
90f9c4501f5873b16b8f33771982a64ca082de43453fc95504da20071a9950be mass_balance.bvh $mass/data/motion/balance.bvh
b8d43a740cd6da419ec0227335627377e69f09d0be2cc2459339d1217e5100d3 mass_cart.bvh $mass/data/motion/cart.bvh
09be8f9bdc47ea2dcd3a31213976d1dfbf859c2635072180adad6cd1838bb428 mass_dance.bvh $mass/data/motion/dance.bvh
3a3fdfeca73cbae69b385eb0635581b741dc775ffde6734daf8b7e02c27119d8 mass_kick.bvh $mass/data/motion/kick.bvh
19e298767bbd4136e80a0608f3bbf07805d460d8ea22ab7a606cfff4b8afd395 mass_pirouette.bvh $mass/data/motion/pirouette.bvh
af3e1a0aa2e699d0a80aa9e9369fb365eac15a45ae33a2eea25fb0d251130d86 mass_run.bvh $mass/data/motion/run.bvh
be220794094d14eb08516c5e8257d9335f705414226fe76b580d51d14105511c mass_walk.bvh $mass/data/motion/walk.bvh
efdee596eced33b812287eb38af8a1bec7530dfaf7e8cc25a56d962a8e6a48a1 xia_angry_13_000.bvh $dme/style_transfer/data/xia_test/angry_13_000.bvh
3c14cebcadaf68643a0f89a406fcec8c32a7becb35f58b1b4428149761147964 xia_depressed_13_000.bvh $dme/style_transfer/data/xia_test/depressed_13_000.bvh
f9fbc3f428a1503194ec8032277a2698dd92c9339a73d9915312001bcb6a121c xia_depressed_18_000.bvh $dme/style_transfer/data/xia_test/depressed_18_000.bvh
4e6cc1e0aa8b6b112be25b6aab5db8f176094181280b2c8ebcf903ede66e6e98 xia_example.bvh $dme/blender_rendering/example.bvh
4478943ef87b4b028888beb0ef1db15d48e8bee7422589c0b26a480a34feef7c xia_neutral_01_000.bvh $dme/style_transfer/data/xia_test/neutral_01_000.bvh
7291266064e39b6185ab29fd8c2558c97b470a5856547412bc0dc1f5704cba20 xia_neutral_16_000.bvh $dme/style_transfer/data/xia_test/neutral_16_000.bvh
5487765cab88bd5f92f58f9bc193440753e59a2a11ca5f808148862cfc6860b8 xia_old_13_000.bvh $dme/style_transfer/data/xia_test/old_13_000.bvh
a5d7b30df527adc37365e9609f2356ca6c1d6e07eced08dc4dee982011d39215 xia_sexy_01_000.bvh $dme/style_transfer/data/xia_test/sexy_01_000.bvh
83deeb93b4086eef64bea486a553683c2df2c23697f9b19d6dd52eef8d488dd3 xia_sexy_01_001.bvh $dme/style_transfer/data/xia_test/sexy_01_001.bvh
cedde9200d0676c96a65644b81921dd8f8a8de2489fd5e4bd99abe5f8d02a87b xia_strutting_01_000.bvh $dme/style_transfer/data/xia_test/strutting_01_000.bvh
"
mkdir -p "$dir"
while read -r sum name url; do
  [ -n "$name" ] || continue
  if [ ! -s "$dir/$name" ] || ! echo "$sum  $dir/$name" | sha256sum -c --quiet - 2>/dev/null; then
    curl -fsSL "$url" -o "$dir/$name.part"
    echo "$sum  $dir/$name.part" | sha256sum -c --quiet -
    mv "$dir/$name.part" "$dir/$name"
  fi
done <<< "$files"
ls "$dir"
