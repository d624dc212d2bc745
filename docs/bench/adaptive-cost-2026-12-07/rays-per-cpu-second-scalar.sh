#!/bin/bash
# Interleaved: rays per CPU second of uniform and the default adaptive rule with path (wavefront)
# and path-scalar (one path at a time: no batches to shrink), 1 thread.
cd "$(dirname "$0")/../../.."  # the repository root

out=${OUT:-/tmp}/rays-per-cpu-second-scalar.txt
for round in 1 2 3; do
  for s in scenes/bench/heavy-helmets.gltf scenes/bench/sun-helmets.gltf; do
    n=$(basename $s .gltf)
    for integ in path path-scalar; do
      for m in uniform default; do
        a="--spp 64"; [ $m = default ] && a="--spp 256 --noise-threshold 0.02"
        line=$( { /usr/bin/time -f "TIME %U %S" ./build/tray-render --integrator $integ --sampler sobol --pixel-sampler sequence --threads 1 --allow-any-path --resolution 320x240 $a $s -o ${OUT:-/tmp}/sc.exr; } 2>&1 | tr '\n' ' ')
        echo "$n $integ-$m $round $line" >> $out
      done
    done
  done
done
echo DONE >> $out
