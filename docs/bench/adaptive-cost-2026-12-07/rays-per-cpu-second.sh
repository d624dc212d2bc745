#!/bin/bash
# Interleaved: rays per CPU second (1 thread) of uniform and four adaptive variants at one threshold.
# The cost and widecost lines need --noise-cost, in commit 5e5be4d (reverted): build that commit.
cd "$(dirname "$0")/../../.."  # the repository root
T=${T:-0.02}
out=${OUT:-/tmp}/rays-per-cpu-second.txt
for round in 1 2 3; do
  for s in scenes/bench/heavy-helmets.gltf scenes/bench/sun-helmets.gltf ../shared/reference/cornell-box.gltf; do
    n=$(basename $s .gltf)
    for m in uniform default cost wide widecost; do
      case $m in
        uniform) a="--spp 64";;
        default) a="--spp 256 --noise-threshold $T";;
        cost) a="--spp 256 --noise-threshold $T --noise-cost rays";;
        wide) a="--spp 256 --noise-threshold $T --noise-decision wide";;
        widecost) a="--spp 256 --noise-threshold $T --noise-decision wide --noise-cost rays";;
      esac
      line=$( { /usr/bin/time -f "TIME %U %S" ./build/tray-render --integrator path --sampler sobol --pixel-sampler sequence --threads 1 --allow-any-path --resolution 320x240 $a $s -o ${OUT:-/tmp}/rp.exr; } 2>&1 | tr '\n' ' ')
      echo "$n $m $round $line" >> $out
    done
  done
done
echo DONE >> $out
