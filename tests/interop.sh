#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# make interop: open packexport's files in the programs they are meant for, where installed.
# Usage: sh tests/interop.sh BINDIR
#
# Always: python3's own parsers (xml.etree for VTK, plain text for LAMMPS and YADE).
# If present: ParaView (pvpython: XMLPolyDataReader, XMLMultiBlockDataReader; the plates
# .vtp: closed boxes of the right volume and area), OVITO (ovitos
# or the python module ovito: LAMMPS dump and data, VTP), YADE (SpherePack.load), LAMMPS
# (lmp, lmp_serial: read_data).  Prints one PASS/FAIL line per check, which readers were
# found and ran, and a closing "N passed, N failed"; exits 1 if anything failed.
set -u
bin=${1:?usage: sh tests/interop.sh BINDIR}
bin=$(cd "$bin" && pwd) || exit 1
PATH="$bin:$PATH"
export LC_ALL=C
work=$(mktemp -d "${TMPDIR:-/tmp}/qusgm-interop.XXXXXX") || exit 1
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

passed=0
failed=0
ran=""
missing=""
pass() { echo "PASS $1"; passed=$((passed + 1)); }
fail() { echo "FAIL $1: $2"; failed=$((failed + 1)); }
# check NAME CMD...: PASS when CMD exits 0 (its output kept in check.log).
check() {
	cname=$1
	shift
	if "$@" >check.log 2>&1; then pass "$cname"; else fail "$cname" "$(tail -n 5 check.log | tr '\n' '|')"; fi
}

# A 5 x 5 x 4 lattice of 0.5 mm spheres 0.99 mm apart: every neighbour pair overlaps, and
# the layer z = 0.5 mm touches nothing but the box, which is fitted around the spheres.
awk 'BEGIN { for (i = 0; i < 5; i++) for (j = 0; j < 5; j++) for (k = 0; k < 4; k++)
	printf "%.17g %.17g %.17g 0.0005\n", 0.0005 + 0.00099 * i, 0.0005 + 0.00099 * j, 0.0005 + 0.00099 * k }' >lattice.txt
n=100
if ! packimport -o in.pack lattice.txt 2>err.txt ||
    ! packexport --vtk -o set.vtm in.pack 2>>err.txt ||
    ! packexport --lammps -o in.dump in.pack 2>>err.txt ||
    ! packexport --lammps-data -o in.data in.pack 2>>err.txt ||
    ! packexport --xyzr --periodic -o in.xyzr in.pack 2>>err.txt; then
	fail "exports" "$(cat err.txt)"
	echo "$passed passed, $failed failed"
	exit 1
fi
nc=$(grep -o 'NumberOfLines="[0-9]*"' set_contacts.vtp | tr -dc 0-9)
echo "pack: $n grains, $nc contacts"

# --- python3 parsers (always) ----------------------------------------------------------
if command -v python3 >/dev/null 2>&1; then
	ran="$ran python3"
	cat >parse.py <<'EOF'
import sys, xml.etree.ElementTree as ET
n, nc = int(sys.argv[1]), int(sys.argv[2])
def piece(path):
    return ET.parse(path).getroot().find("PolyData").find("Piece")
g = piece("set_grains.vtp")
assert int(g.get("NumberOfPoints")) == n and int(g.get("NumberOfVerts")) == n
pts = g.find("Points").find("DataArray").text.split()
assert len(pts) == 3 * n
ids = [a for a in g.find("PointData") if a.get("Name") == "id"][0].text.split()
assert ids == [str(i) for i in range(1, n + 1)]
c = piece("set_contacts.vtp")
assert int(c.get("NumberOfLines")) == nc and int(c.get("NumberOfPoints")) == 2 * nc
for a in c.find("CellData"):
    assert len(a.text.split()) == nc, a.get("Name")
m = ET.parse("set.vtm").getroot()
assert [d.get("file") for d in m.iter("DataSet")] == ["set_grains.vtp", "set_contacts.vtp"]
d = open("in.dump").read().split("\n")
assert int(d[d.index("ITEM: NUMBER OF ATOMS") + 1]) == n
i = d.index("ITEM: ATOMS id type x y z radius")
assert len([l for l in d[i + 1:] if l.strip()]) == n
t = open("in.data").read().split("\n")
assert int(t[2].split()[0]) == n and t[2].split()[1] == "atoms"
i = t.index("Atoms # sphere")
assert len([l for l in t[i + 1:] if l.strip()]) == n
x = open("in.xyzr").read().split("\n")
assert x[0].startswith("##PERIODIC:: ") and len(x[0].split()) == 4
assert len([l for l in x[1:] if l.strip()]) == n and all(len(l.split()) == 4 for l in x[1:] if l)
EOF
	check "python3: VTK XML, LAMMPS dump and data, xyzr parse with the right counts" python3 parse.py "$n" "$nc"
else
	missing="$missing python3"
	fail "python3" "not found; the always-run parsers need it"
fi

# --- ParaView --------------------------------------------------------------------------
if command -v pvpython >/dev/null 2>&1; then
	ran="$ran pvpython"
	cat >pv.py <<'EOF'
import sys
from paraview.simple import XMLPolyDataReader, XMLMultiBlockDataReader
from paraview import servermanager
n, nc = int(sys.argv[1]), int(sys.argv[2])
g = XMLPolyDataReader(FileName=["set_grains.vtp"])
g.UpdatePipeline()
gi = g.GetDataInformation()
assert gi.GetNumberOfPoints() == n and gi.GetNumberOfCells() == n, (gi.GetNumberOfPoints(), gi.GetNumberOfCells())
assert sorted(g.PointData.keys()) == ["E", "id", "nu", "radius"], g.PointData.keys()
d = servermanager.Fetch(g)
ids = d.GetPointData().GetArray("id")
assert ids.GetDataTypeSize() == 8 and ids.GetValue(n - 1) == n
c = XMLPolyDataReader(FileName=["set_contacts.vtp"])
c.UpdatePipeline()
ci = c.GetDataInformation()
assert ci.GetNumberOfPoints() == 2 * nc and ci.GetNumberOfCells() == nc, (ci.GetNumberOfPoints(), ci.GetNumberOfCells())
assert sorted(c.CellData.keys()) == ["id1", "id2", "normal_force", "overlap"], c.CellData.keys()
m = XMLMultiBlockDataReader(FileName=["set.vtm"])
m.UpdatePipeline()
mi = m.GetDataInformation()
assert mi.GetNumberOfPoints() == n + 2 * nc, mi.GetNumberOfPoints()
print("paraview: %d grain points, %d contact lines, %d points in the .vtm" % (gi.GetNumberOfPoints(), ci.GetNumberOfCells(), mi.GetNumberOfPoints()))
EOF
	check "pvpython: XMLPolyDataReader (grains, contacts), XMLMultiBlockDataReader (.vtm)" pvpython pv.py "$n" "$nc"
	grep '^paraview:' check.log
else
	missing="$missing pvpython"
fi

# --- ParaView: spheroplates -------------------------------------------------------------
# 27 plates on a 3 x 3 x 3 grid, turned by quaternions made from awk's sines (normalised
# to the last bits, so the reader takes them), the middle one a sphere (side 0): the .vtp of
# closed boxes must read, be closed (no boundary or non-manifold edge), and enclose the
# boxes' volume and area, sum (L + 2r)^2 2r and sum 2 (L + 2r)^2 + 8 r (L + 2r).
awk 'BEGIN {
	print "qusgm-pack 2\nunits SI\nbox 0 0 0 3e-3 3e-3 3e-3\nboundary walls walls walls\nwalls 7e12 0.495 0.3"
	print "friction 0.3\ngrains 27\ncontacts 0\ncolumns id x y z r E nu rho side qw qx qy qz\nend"
	for (k = 0; k < 27; k++) {
		a = 0.7 * k + 0.3; b = 1.3 * k + 0.1; h = 0.37 * k
		w = cos(h); x = sin(h) * sin(a) * cos(b); y = sin(h) * sin(a) * sin(b); z = sin(h) * cos(a)
		n = sqrt(w * w + x * x + y * y + z * z)
		printf "%d %.17g %.17g %.17g %.17g 7e10 0.2 2420 %.17g %.17g %.17g %.17g %.17g\n", k + 1,
		    5e-4 + 1e-3 * (k % 3), 5e-4 + 1e-3 * (int(k / 3) % 3), 5e-4 + 1e-3 * int(k / 9),
		    2e-5 + 1e-6 * k, k == 13 ? 0 : 3e-4 + 1e-5 * k, w / n, x / n, y / n, z / n
	} }' >plates.pack
if command -v pvpython >/dev/null 2>&1 && packexport --vtk -o plates.vtp plates.pack 2>err.txt; then
	cat >pvplates.py <<'PYEOF'
from paraview.simple import XMLPolyDataReader
from paraview import servermanager
from vtkmodules.vtkFiltersCore import vtkFeatureEdges, vtkMassProperties, vtkTriangleFilter
g = [l.split() for l in open("plates.pack") if len(l.split()) == 13]
n = len(g)
r = XMLPolyDataReader(FileName=["plates.vtp"])
r.UpdatePipeline()
i = r.GetDataInformation()
assert i.GetNumberOfPoints() == 8 * n and i.GetNumberOfCells() == 6 * n, (i.GetNumberOfPoints(), i.GetNumberOfCells())
assert sorted(r.CellData.keys()) == ["E", "id", "normal", "nu", "radius", "side"], r.CellData.keys()
d = servermanager.Fetch(r)
fe = vtkFeatureEdges()
fe.SetInputData(d)
fe.BoundaryEdgesOn()
fe.NonManifoldEdgesOn()
fe.FeatureEdgesOff()
fe.ManifoldEdgesOff()
fe.Update()
assert fe.GetOutput().GetNumberOfCells() == 0, fe.GetOutput().GetNumberOfCells()
t = vtkTriangleFilter()
t.SetInputData(d)
t.Update()
m = vtkMassProperties()
m.SetInputData(t.GetOutput())
m.Update()
V = sum((float(x[8]) + 2 * float(x[4])) ** 2 * 2 * float(x[4]) for x in g)
A = sum(2 * (float(x[8]) + 2 * float(x[4])) ** 2 + 8 * float(x[4]) * (float(x[8]) + 2 * float(x[4])) for x in g)
assert abs(m.GetVolume() - V) < 1e-9 * V and abs(m.GetSurfaceArea() - A) < 1e-9 * A, (m.GetVolume(), V, m.GetSurfaceArea(), A)
print("paraview: %d plates as %d closed quadrilaterals, volume %.6g m^3, area %.6g m^2" % (n, 6 * n, V, A))
PYEOF
	check "pvpython: plates .vtp reads, closed boxes of the plates' volume and area" pvpython pvplates.py
	grep '^paraview:' check.log
elif command -v pvpython >/dev/null 2>&1; then
	fail "plates export" "$(cat err.txt)"
fi

# --- OVITO -----------------------------------------------------------------------------
ovito=""
if command -v ovitos >/dev/null 2>&1; then
	ovito=ovitos
elif command -v python3 >/dev/null 2>&1 && python3 -c 'import ovito' >/dev/null 2>&1; then
	ovito=python3
fi
if [ -n "$ovito" ]; then
	ran="$ran ovito($ovito)"
	cat >ov.py <<'EOF'
import sys
from ovito.io import import_file
n = int(sys.argv[1])
for path, kw in (("in.dump", {}), ("in.data", {"atom_style": "sphere"}), ("set_grains.vtp", {})):
    d = import_file(path, **kw).compute()
    assert d.particles.count == n, (path, d.particles.count)
    print("ovito: %s: %d particles" % (path, d.particles.count))
EOF
	check "ovito: LAMMPS dump, LAMMPS data (sphere), VTP particles" "$ovito" ov.py "$n"
	grep '^ovito:' check.log
else
	missing="$missing ovito"
fi

# --- YADE ------------------------------------------------------------------------------
if command -v yade >/dev/null 2>&1; then
	ran="$ran yade"
	cat >yd.py <<'EOF'
import sys
from yade import pack
sp = pack.SpherePack()
sp.load("in.xyzr")
print("yade: %d spheres, cell %s" % (len(sp), sp.cellSize))
assert len(sp) == int(open("n.txt").read())
sys.exit(0)
EOF
	echo "$n" >n.txt
	check "yade: SpherePack.load of --xyzr --periodic" yade -n -x yd.py
	grep '^yade:' check.log
else
	missing="$missing yade"
fi

# --- LAMMPS ----------------------------------------------------------------------------
lmp=""
for l in lmp lmp_serial lmp_stable; do
	if command -v $l >/dev/null 2>&1; then lmp=$l; break; fi
done
if [ -n "$lmp" ]; then
	ran="$ran $lmp"
	printf 'units si\natom_style sphere\nboundary f f f\nread_data in.data\nvariable n equal count(all)\nprint "lammps: atoms ${n}"\n' >in.lmp
	check "lammps: read_data of --lammps-data" "$lmp" -log none -in in.lmp
	if ! grep -q "^lammps: atoms $n\$" check.log; then fail "lammps: atom count" "$(grep '^lammps:' check.log)"; fi
else
	missing="$missing lammps"
fi

echo "readers run:${ran:- none}"
echo "readers not found:${missing:- none}"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
