#!/bin/sh
# make run: the default job on built-in defaults.  Generates the G2740-style loose glass
# pack, prints its packinfo and writes a VTK export, all under out/.
set -e
bin=${1:-build/bin}
mkdir -p out
echo "packgen -n 2740 --seed 1 --material glass -o out/loose.pack   (DEM compaction, about a minute)"
"$bin/packgen" -n 2740 --seed 1 --material glass -o out/loose.pack
echo "packinfo out/loose.pack"
"$bin/packinfo" out/loose.pack
"$bin/packexport" --vtk -o out/loose.vtm out/loose.pack
echo "wrote out/loose.pack and out/loose.vtm (+ out/loose_grains.vtp, out/loose_contacts.vtp) for ParaView/OVITO"
