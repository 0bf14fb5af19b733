# SPDX-License-Identifier: GPL-3.0-or-later
# packexport: VTK, LAMMPS and xyzr output, checked by parsing it back; usage and data errors.
. "$TOP/tests/tools/lib.sh"

# Four grains with sparse ids: 5 and 9 overlap by 0.02, 12 overlaps the zhi wall by 0.05,
# 20 touches nothing.
cat >in.pack <<'EOF'
qusgm-pack 1
units SI
box 0 0 0 1 1 1
walls 7000000000000 0.495 0.3
friction 0.3
grains 4
contacts 0
end
5 0.2 0.2 0.2 0.1 70000000000 0.2 2420
9 0.38 0.2 0.2 0.1 60000000000 0.25 2420
12 0.5 0.5 0.95 0.1 70000000000 0.2 2500
20 0.5 0.8 0.5 0.05 70000000000 0.2 2420
EOF
# id x y z r, as the pack writes them
awk 'f { print $1, $2, $3, $4, $5 } $1 == "end" { f = 1 }' in.pack >cols.ref
awk '{ print $2, $3, $4, $5 }' cols.ref >xyzr.ref

have_py=0
if command -v python3 >/dev/null 2>&1; then have_py=1; else echo "note: python3 missing, XML and LAMMPS parse checks skipped"; fi

# --- VTK -------------------------------------------------------------------------------
expect_ok "vtk -o NAME.vtm" packexport --vtk -o set.vtm in.pack
if [ -f set.vtm ] && [ -f set_grains.vtp ] && [ -f set_contacts.vtp ]; then
	pass "vtk -o NAME.vtm writes NAME.vtm, NAME_grains.vtp, NAME_contacts.vtp"
else
	fail "vtk -o NAME.vtm writes three files" "$(ls)"
fi
if ls -a | grep -q '^\.set'; then fail "vtk leaves no temporary files" "$(ls -a)"; else pass "vtk leaves no temporary files"; fi
packexport --vtk in.pack >stdout.vtp
expect_same "vtk stdout is the grains .vtp" stdout.vtp set_grains.vtp
packexport --vtk -o only.vtp in.pack
expect_same "vtk -o NAME.vtp is the grains .vtp" only.vtp set_grains.vtp
packexport --vtk -o again.vtm in.pack
expect_same "vtk output is deterministic" again_contacts.vtp set_contacts.vtp
# all three files or none: the contacts' file fails to write (a link to /dev/full), and the
# grains' file, written first, must not be left behind; a name that cannot be written is
# refused before any work
ln -s /dev/full full_contacts.vtp
expect_error "vtk -o NAME.vtm, the contacts' file fails" 1 '^packexport: full_contacts\.vtp: write error: No space left on device$' \
    packexport --vtk -o full.vtm in.pack
if [ ! -e full.vtm ] && [ ! -e full_grains.vtp ] && ! ls -a | grep -q '^\.full'; then pass "vtk: a failed file leaves none of the three"; else fail "vtk: a failed file leaves none of the three" "$(ls -a | tr '\n' ' ')"; fi
mkdir dir_contacts.vtp
expect_refused "none of the three written" "nothing.vtm" "vtk -o NAME.vtm, NAME_contacts.vtp a directory" 2 "^packexport: the contacts' .vtp of -o: 'dir_contacts.vtp' is a directory" \
    packexport --vtk -o dir.vtm in.pack
if [ ! -e dir.vtm ] && [ ! -e dir_grains.vtp ]; then pass "vtk: refused before any file"; else fail "vtk: refused before any file" "$(ls)"; fi
cp in.pack in2.pack
expect_error "-o the input" 2 "^packexport: -o 'in2.pack' is the input" packexport --xyzr -o in2.pack in2.pack
expect_same "-o the input: the input untouched" in2.pack in.pack

if [ "$have_py" = 1 ]; then
	cat >check_vtk.py <<'EOF'
import sys, math, xml.etree.ElementTree as ET
ref = [l.split() for l in open("cols.ref")]
def arrays(piece, section):
    return {a.get("Name"): a.text.split() for a in piece.find(section).findall("DataArray")}
def piece(path):
    root = ET.parse(path).getroot()
    assert root.get("type") == "PolyData" and root.get("version") == "1.0", root.attrib
    for a in root.iter("DataArray"):
        assert a.get("format") == "ascii", a.attrib
    return root.find("PolyData").find("Piece")
def check_cells(p, kind, n, k):
    c = arrays(p, kind)
    assert c["connectivity"] == [str(i) for i in range(n * k)], c["connectivity"]
    assert c["offsets"] == [str(k * (i + 1)) for i in range(n)], c["offsets"]
what = sys.argv[1]
if what == "grains":
    p = piece("set_grains.vtp")
    n = len(ref)
    assert p.get("NumberOfPoints") == str(n) and p.get("NumberOfVerts") == str(n), p.attrib
    pd = arrays(p, "PointData")
    assert pd["id"] == [r[0] for r in ref], pd["id"]
    assert pd["radius"] == [r[4] for r in ref], pd["radius"]
    assert len(pd["E"]) == n and len(pd["nu"]) == n
    types = {a.get("Name"): a.get("type") for a in p.find("PointData")}
    assert types == {"id": "Int64", "radius": "Float64", "E": "Float64", "nu": "Float64"}, types
    pts = list(arrays(p, "Points").values())[0]
    assert pts == [v for r in ref for v in r[1:4]], pts
    check_cells(p, "Verts", n, 1)
elif what == "contacts":
    p = piece("set_contacts.vtp")
    assert p.get("NumberOfLines") == "2" and p.get("NumberOfPoints") == "4", p.attrib
    cd = arrays(p, "CellData")
    assert cd["id1"] == ["5", "12"] and cd["id2"] == ["9", "-6"], (cd["id1"], cd["id2"])
    h = [float(v) for v in cd["overlap"]]
    assert abs(h[0] - 0.02) < 1e-12 and abs(h[1] - 0.05) < 1e-12, h
    # Hertz: P = 4/3 E* sqrt(R*) h^1.5
    def estar(E1, n1, E2, n2): return 1 / ((1 - n1 * n1) / E1 + (1 - n2 * n2) / E2)
    P = [4 / 3 * estar(7e10, 0.2, 6e10, 0.25) * math.sqrt(0.05) * h[0] ** 1.5,
         4 / 3 * estar(7e10, 0.2, 7e12, 0.495) * math.sqrt(0.1) * h[1] ** 1.5]
    got = [float(v) for v in cd["normal_force"]]
    assert all(abs(g - w) <= 1e-9 * w for g, w in zip(got, P)), (got, P)
    pts = [float(v) for v in list(arrays(p, "Points").values())[0]]
    want = [0.2, 0.2, 0.2, 0.38, 0.2, 0.2, 0.5, 0.5, 0.95, 0.5, 0.5, 1.0]
    assert all(abs(a - b) < 1e-15 for a, b in zip(pts, want)) and len(pts) == 12, pts
    check_cells(p, "Lines", 2, 2)
elif what == "vtm":
    root = ET.parse("set.vtm").getroot()
    assert root.get("type") == "vtkMultiBlockDataSet" and root.get("version") == "1.0", root.attrib
    ds = root.find("vtkMultiBlockDataSet").findall("DataSet")
    assert [d.get("file") for d in ds] == ["set_grains.vtp", "set_contacts.vtp"], [d.attrib for d in ds]
    assert [d.get("index") for d in ds] == ["0", "1"]
EOF
	for part in grains contacts vtm; do
		if python3 check_vtk.py $part >py.out 2>&1; then pass "vtk $part parses, counts and ids right"; else fail "vtk $part" "$(tail -n 3 py.out)"; fi
	done
fi

# --- LAMMPS ----------------------------------------------------------------------------
expect_ok "lammps dump" packexport --lammps -o out.dump in.pack
awk '/^ITEM: ATOMS/ { f = 1; next } f { print $1, $3, $4, $5, $6 }' out.dump >dump.cols
expect_same "lammps dump atoms parse back to the pack's ids, centres, radii" dump.cols cols.ref
if head -n 1 out.dump | grep -q '^ITEM: TIMESTEP$' && grep -q '^ITEM: BOX BOUNDS ff ff ff$' out.dump &&
    grep -q '^ITEM: ATOMS id type x y z radius$' out.dump &&
    [ "$(sed -n '/^ITEM: NUMBER OF ATOMS/{n;p;}' out.dump)" = 4 ] &&
    [ "$(sed -n '/^ITEM: BOX BOUNDS/{n;p;}' out.dump)" = "0 1" ]; then
	pass "lammps dump header items"
else
	fail "lammps dump header items" "$(head -n 9 out.dump | tr '\n' '|')"
fi
cat in.pack in.pack | packexport --lammps >two.dump
expect_num "lammps dump: two packs give two frames" "$(grep -c '^ITEM: TIMESTEP' two.dump)" == 2
expect_num "lammps dump: second frame is timestep 1" "$(awk '/^ITEM: TIMESTEP/ { getline; t = $1 } END { print t }' two.dump)" == 1

expect_ok "lammps data" packexport --lammps-data -o out.data in.pack
if [ "$have_py" = 1 ]; then
	cat >check_data.py <<'EOF'
ref = [l.split() for l in open("cols.ref")]
lines = open("out.data").read().split("\n")
head = {}
for l in lines[1:]:
    w = l.split()
    if l.startswith("Atoms"):
        break
    if len(w) == 2 and w[1] == "atoms": head["atoms"] = int(w[0])
    if len(w) == 3 and w[1:] == ["atom", "types"]: head["types"] = int(w[0])
    if len(w) == 4 and w[2].endswith("lo"): head[w[2]] = (float(w[0]), float(w[1]))
assert head == {"atoms": 4, "types": 1, "xlo": (0, 1), "ylo": (0, 1), "zlo": (0, 1)}, head
i = lines.index("Atoms # sphere")
atoms = [l.split() for l in lines[i + 1:] if l.strip()]
assert len(atoms) == 4, atoms
rho = ["2420", "2420", "2500", "2420"]
for a, r, d in zip(atoms, ref, rho):
    # id type diameter density x y z
    assert a[0] == r[0] and a[1] == "1" and a[3] == d, (a, r)
    assert a[4:7] == r[1:4], (a, r)
    assert float(a[2]) == 2 * float(r[4]), (a, r)
EOF
	if python3 check_data.py >py.out 2>&1; then pass "lammps data parses back to the pack"; else fail "lammps data parses back" "$(tail -n 3 py.out)"; fi
fi
sed 's/^5 0.2 0.2 0.2/0 0.2 0.2 0.2/' in.pack >id0.pack
expect_error "lammps refuses grain id 0" 1 '^packexport: id0.pack: grain id 0: LAMMPS atom ids must be positive$' packexport --lammps-data id0.pack
packexport --lammps -o bad.dump id0.pack 2>/dev/null
if [ -e bad.dump ] || ls -a | grep -q '^\.bad'; then fail "failed export leaves no file" "$(ls -a)"; else pass "failed export leaves no file"; fi

# --- xyzr ------------------------------------------------------------------------------
packexport --xyzr in.pack >out.xyzr
expect_same "xyzr is exactly the pack's x y z r" out.xyzr xyzr.ref
packexport --xyzr --periodic in.pack >per.xyzr
if [ "$(head -n 1 per.xyzr)" = "##PERIODIC:: 1 1 1" ] && tail -n +2 per.xyzr | cmp -s - xyzr.ref; then
	pass "xyzr --periodic adds one ##PERIODIC:: line"
else
	fail "xyzr --periodic" "$(head -n 2 per.xyzr | tr '\n' '|')"
fi
if grep -v '^##PERIODIC:: ' per.xyzr | grep -q '#'; then fail "xyzr has no other comments" "found '#'"; else pass "xyzr has no other comments"; fi
packexport --xyzr -o out.xyzr.gz in.pack
if gzip -dc out.xyzr.gz | cmp -s - xyzr.ref; then pass "-o NAME.gz compresses"; else fail "-o NAME.gz compresses" "differs"; fi
gzip -c in.pack >in.pack.gz
packexport --xyzr in.pack.gz >gz.xyzr
expect_same "gzip-compressed pack input" gz.xyzr xyzr.ref

# --- errors ----------------------------------------------------------------------------
expect_error "no format is a usage error" 2 'exactly one of' packexport in.pack
expect_error "two formats are a usage error" 2 'exactly one of' packexport --vtk --xyzr in.pack
expect_error "--periodic without --xyzr" 2 'periodic' packexport --lammps --periodic in.pack
expect_error "--vtk -o needs .vtm or .vtp" 2 '\.vtm' packexport --vtk -o out.txt in.pack
expect_error "unknown option" 2 "unknown option '--bogus'" packexport --xyzr --bogus in.pack
expect_error "missing input file" 1 '^packexport: nonexistent.pack: ' packexport --xyzr nonexistent.pack
printf 'qusgm-pack 1\nunits SI\nbox 0 0 0 1 1 1\n' >trunc.pack
expect_error "truncated pack" 1 '^packexport: trunc.pack:4: ' packexport --vtk trunc.pack
: >empty.pack
expect_error "empty input" 1 '^packexport: <stdin>:1: ' packexport --xyzr <empty.pack
cat in.pack in.pack >two.pack
expect_error "xyzr takes one pack" 1 '^packexport: two.pack:[0-9]+: a second pack' packexport --xyzr two.pack

# --- spheroplates ----------------------------------------------------------------------
# Four grains with sparse ids: plates flat, turned 90 degrees about x, turned about an
# oblique axis (a quaternion with no short decimal form), and a sphere (side 0).
cat >plates.pack <<'EOF2'
qusgm-pack 2
units SI
box 0 0 0 1 1 1
boundary walls walls walls
walls 7000000000000 0.495 0.3
friction 0.3
grains 4
contacts 0
columns id x y z r E nu rho side qw qx qy qz
end
3 0.2 0.2 0.2 0.01 70000000000 0.2 2420 0.1 1 0 0 0
8 0.5 0.5 0.5 0.02 60000000000 0.25 2420 0.15 0.7071067811865476 0.7071067811865476 0 0
11 0.8 0.3 0.6 0.005 70000000000 0.2 2500 0.05 0.18257418583505536 0.3651483716701107 0.5477225575051661 0.7302967433402214
14 0.3 0.8 0.7 0.04 70000000000 0.2 2420 0 1 0 0 0
EOF2
# id x y z r side qw qx qy qz, as the pack writes them
awk 'f { print $1, $2, $3, $4, $5, $9, $10, $11, $12, $13 } $1 == "end" { f = 1 }' plates.pack >plates.ref

expect_ok "plates: vtk" packexport --vtk -o plates.vtp plates.pack
packexport --vtk plates.pack >plates-stdout.vtp
expect_same "plates: vtk stdout is the .vtp" plates-stdout.vtp plates.vtp
if [ "$have_py" = 1 ]; then
	# An independent reader: the XML, the counts, and the geometry of every box against R(q)
	# computed here from the quaternion (not through lib/base/quat.h).  Coordinates are
	# O(1) and every step a few roundings, so 1e-12 holds with room.
	cat >check_plates.py <<'EOF2'
import math, xml.etree.ElementTree as ET
ref = [[float(v) for v in l.split()] for l in open("plates.ref")]
root = ET.parse("plates.vtp").getroot()
assert root.get("type") == "PolyData" and root.get("version") == "1.0", root.attrib
p = root.find("PolyData").find("Piece")
n = len(ref)
assert p.get("NumberOfPoints") == str(8 * n) and p.get("NumberOfPolys") == str(6 * n), p.attrib
assert p.get("NumberOfVerts") == "0" and p.get("NumberOfLines") == "0", p.attrib
def arrays(section):
    return {a.get("Name"): (a.get("type"), a.get("NumberOfComponents", "1"), a.text.split()) for a in p.find(section).findall("DataArray")}
cd = arrays("CellData")
assert sorted(cd) == ["E", "id", "normal", "nu", "radius", "side"], sorted(cd)
assert cd["id"][0] == "Int64" and cd["normal"][1] == "3", (cd["id"][:2], cd["normal"][:2])
for name, k in (("id", 0), ("radius", 4), ("side", 5)):
    vals = [float(v) for v in cd[name][2]]
    assert vals == [r[k] for r in ref for f in range(6)], (name, vals)
pts = [float(v) for v in p.find("Points").find("DataArray").text.split()]
pts = [pts[3 * k:3 * k + 3] for k in range(8 * n)]
polys = arrays("Polys")
conn = [int(v) for v in polys["connectivity"][2]]
assert [int(v) for v in polys["offsets"][2]] == [4 * (c + 1) for c in range(6 * n)]
sub = lambda a, b: [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
dot = lambda a, b: a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
cross = lambda a, b: [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
norm = lambda a: math.sqrt(dot(a, a))
def rot(w, x, y, z):   # columns: the body axes in the lab
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
tol = 1e-12
nrm = [float(v) for v in cd["normal"][2]]
for g, r in enumerate(ref):
    c, rad, L, R = r[1:4], r[4], r[5], rot(*r[6:10])
    e = [[R[0][k], R[1][k], R[2][k]] for k in range(3)]
    corners = pts[8 * g:8 * g + 8]
    mid = [sum(q[a] for q in corners) / 8 for a in range(3)]
    assert norm(sub(mid, c)) < tol, ("centre", g, mid, c)
    kinds = []
    for f in range(6):
        ids = conn[4 * (6 * g + f):4 * (6 * g + f) + 4]
        assert all(8 * g <= i < 8 * g + 8 for i in ids), ("a face uses another grain's points", g, ids)
        q = [pts[i] for i in ids]
        nf = cross(sub(q[1], q[0]), sub(q[2], q[0]))
        nf = [v / norm(nf) for v in nf]
        assert all(abs(dot(sub(v, q[0]), nf)) < tol for v in q), ("face not planar", g, f)
        edges = [norm(sub(q[(k + 1) % 4], q[k])) for k in range(4)]
        assert abs(edges[0] - edges[2]) < tol and abs(edges[1] - edges[3]) < tol, ("not a rectangle", g, f, edges)
        assert abs(norm(sub(q[2], q[0])) - norm(sub(q[3], q[1]))) < tol, ("diagonals differ", g, f)
        fc = [sum(v[a] for v in q) / 4 for a in range(3)]
        assert dot(sub(fc, c), nf) > 0, ("face turned inward", g, f)
        assert all(abs(float(x) - y) < tol for x, y in zip(nrm[18 * g + 3 * f:18 * g + 3 * f + 3], e[2])), ("normal array", g, f)
        if abs(abs(dot(nf, e[2])) - 1) < tol:
            # a face of the plate: a square of side L + 2r, normal +-R(q) e3, r from the centre,
            # edges along R(q) e1 and e2
            assert all(abs(s - (L + 2 * rad)) < tol for s in edges), ("face side", g, f, edges, L + 2 * rad)
            assert abs(abs(dot(sub(fc, c), e[2])) - rad) < tol and norm(cross(sub(fc, c), e[2])) < tol, ("face offset", g, f)
            u = sub(q[1], q[0])
            assert abs(abs(dot(u, e[0])) - norm(u)) < tol or abs(abs(dot(u, e[1])) - norm(u)) < tol, ("edge direction", g, f)
            kinds.append(2)
        else:
            # a rim face: (L + 2r) by 2r, normal +-R(q) e1 or e2, L/2 + r from the centre
            want = sorted([L + 2 * rad, L + 2 * rad, 2 * rad, 2 * rad])
            assert all(abs(a - b) < tol for a, b in zip(sorted(edges), want)), ("rim sides", g, f, edges, want)
            k = 0 if abs(abs(dot(nf, e[0])) - 1) < tol else 1
            assert abs(abs(dot(nf, e[k])) - 1) < tol, ("rim normal", g, f)
            assert abs(dot(sub(fc, c), nf) - (L / 2 + rad)) < tol, ("rim offset", g, f)
            kinds.append(k)
    assert sorted(kinds) == [0, 0, 1, 1, 2, 2], ("two faces and four rim faces, one per side", g, kinds)
print("ok")
EOF2
	if python3 check_plates.py >py.out 2>&1; then pass "plates: vtk boxes: planar faces, squares of side L + 2r, normals R(q) e3, outward"; else fail "plates: vtk geometry" "$(tail -n 3 py.out)"; fi
fi
expect_ok "plates: lammps dump" packexport --lammps -o plates.dump plates.pack
if grep -q '^ITEM: ATOMS id type x y z quatw quati quatj quatk shapex shapey shapez$' plates.dump; then
	pass "plates: lammps dump columns for OVITO's orientation and shape"
else
	fail "plates: lammps dump columns" "$(grep '^ITEM: ATOMS' plates.dump)"
fi
# id type x y z q(4) then L + 2r, L + 2r, 2r: checked against the pack with awk's own numbers
awk 'NR == FNR { L[$1] = $6 + 2 * $5; T[$1] = 2 * $5; C[$1] = $2 " " $3 " " $4 " " $7 " " $8 " " $9 " " $10; S[$1] = $6; next }
    /^ITEM: ATOMS/ { f = 1; next }
    f { n++; c = $3 " " $4 " " $5 " " $6 " " $7 " " $8 " " $9
        if (!($1 in C) || c != C[$1] || $10 != L[$1] || $11 != L[$1] || $12 != T[$1] || $2 != (S[$1] > 0 ? 1 : 2)) bad = bad " " $1 }
    END { if (bad || n != 4) { print "bad:" bad " n=" n; exit 1 } }' plates.ref plates.dump >awk.out 2>&1
if [ $? -eq 0 ]; then pass "plates: lammps dump: centres, quaternions, extents L+2r L+2r 2r, type 2 for the sphere"; else fail "plates: lammps dump values" "$(cat awk.out)"; fi
cat plates.pack plates.pack | packexport --lammps >plates2.dump
expect_num "plates: lammps dump: two packs give two frames" "$(grep -c '^ITEM: ATOMS id type x y z quatw' plates2.dump)" == 2
expect_error "plates: xyzr refuses plates" 1 '^packexport: plates\.pack: grain 3 is a spheroplate \(side > 0\); --xyzr handles spheres only$' \
    packexport --xyzr plates.pack
expect_error "plates: lammps-data refuses plates" 1 '^packexport: plates\.pack: grain 3 is a spheroplate \(side > 0\); --lammps-data handles spheres only$' \
    packexport --lammps-data plates.pack

# The force network of plates (-o NAME.vtm): a plate (id 4, L 0.1, r 0.01, flat) under a
# sphere (id 9, r 0.02) centred 0.029 above it, an overlap h = 0.01 + 0.02 - 0.029 = 1e-3 of
# one element (the sphere on the face), and a flat plate (id 12, glued to zlo) whose face lies
# 0.001 into the zlo wall: its 4 corners, each h = 1e-3.  With k_n = 1000 N/m the normal
# forces are k_n h = 1 N and 4 k_n h = 4 N; the pair's contact line gives Q0 = (0.2, 0, 0)
# on 4; the wall's line ends at the corners' mean foot on the wall, (0.25, 0.3, 0).  The
# linear law's (meta contact-law linear: a pack without the key is Hertz-Mindlin's).
cat >pc.pack <<'EOF2'
qusgm-pack 2
meta contact-law linear
meta kn 1000
units SI
box 0 0 0 1 1 1
boundary walls walls walls
walls 7000000000000 0.495 0.3
friction 0.3
grains 3
contacts 1
columns id x y z r E nu rho side qw qx qy qz glued
end
4 0.5 0.5 0.5 0.01 70000000000 0.2 2420 0.1 1 0 0 0 -
9 0.5 0.5 0.529 0.02 70000000000 0.2 2420 0 1 0 0 0 -
12 0.25 0.3 0.009 0.01 70000000000 0.2 2420 0.1 1 0 0 0 zlo
4 9 1 0.2 0 0 0
EOF2
# vtp_array FILE NAME: the values of one DataArray, one tuple a line
vtp_array() { awk -v n="Name=\"$2\"" 'index($0, n) { f = 1; next } f && /<\/DataArray>/ { f = 0 } f' "$1" | tr '\n' ' ' | sed 's/ $//'; }
expect_ok "plates: vtk -o NAME.vtm, the contacts of plates" packexport --vtk -o pc.vtm pc.pack
v1=$(vtp_array pc_contacts.vtp id1) v2=$(vtp_array pc_contacts.vtp id2) el=$(vtp_array pc_contacts.vtp elements)
[ "$v1" = "4 12" ] && [ "$v2" = "9 -5" ] && [ "$el" = "1 4" ] && pass "plates: two interactions, 4-9 of 1 element and 12-zlo of 4" ||
	fail "plates: the interactions" "id1 '$v1' id2 '$v2' elements '$el'"
set -- $(vtp_array pc_contacts.vtp normal_force)
expect_num "plates: normal force of the pair k_n h = 1 N" "$(rel "$1" 1)" "<" 1e-12
expect_num "plates: normal force on the wall 4 k_n h = 4 N" "$(rel "$2" 4)" "<" 1e-12
set -- $(vtp_array pc_contacts.vtp force)
expect_num "plates: the pair's force P n + Q0 = (0.2, 0, -1)" "$(awk -v x="$1" -v y="$2" -v z="$3" 'BEGIN { d = (x - 0.2) ^ 2 + y ^ 2 + (z + 1) ^ 2; print sqrt(d) }')" "<" 1e-12
[ "$(vtp_array pc_contacts.vtp tangential_force)" = "0.2 0 0 0 0 0" ] && pass "plates: the tangential forces, of the contact line and none on the wall" ||
	fail "plates: tangential forces" "$(vtp_array pc_contacts.vtp tangential_force)"
[ "$(vtp_array pc_contacts.vtp Points)" = "0.5 0.5 0.5 0.5 0.5 0.529 0.25 0.3 0.009 0.25 0.3 0" ] &&
	pass "plates: lines centre to centre, and to the foot on the wall" || fail "plates: the line ends" "$(vtp_array pc_contacts.vtp Points)"
[ "$(vtp_array pc_grains.vtp glued | tr ' ' '\n' | sort -u | tr '\n' ' ')" = "0 5 " ] && grep -q 'Name="side"' pc_grains.vtp &&
	pass "plates: the grains' .vtp of -o NAME.vtm are the boxes, with glued (1 + zlo = 5)" || fail "plates: the grains' .vtp" "$(vtp_array pc_grains.vtp glued)"
grep -v '^meta kn' pc.pack >pc0.pack
expect_ok "plates: vtk -o NAME.vtm without meta kn" packexport --vtk -o pc0.vtm pc0.pack
grep -q 'Name="normal_force"' pc0_contacts.vtp && fail "plates: no forces without meta kn" "normal_force written" ||
	pass "plates: no forces without meta kn, the geometry only"
# shape columns with every side 0: spheres, the sphere files byte for byte
awk 'NR == 1 { print "qusgm-pack 2"; next }
    $1 == "end" { print "boundary walls walls walls"; print "columns id x y z r E nu rho side qw qx qy qz"; print; f = 1; next }
    f { print $0, 0, 1, 0, 0, 0; next } { print }' in.pack >in0.pack
for fmt in vtk lammps lammps-data xyzr; do
	packexport --$fmt in.pack >a.out 2>/dev/null
	packexport --$fmt in0.pack >b.out 2>/dev/null
	if [ -s a.out ] && cmp -s a.out b.out; then pass "shape columns with side 0: --$fmt as for spheres"; else fail "shape columns with side 0: --$fmt" "differs"; fi
done

# --- the phase column (issue 20): hydrate grains keep their tag where the format has a type ---
cp "$TOP/tests/fuzz/corpus/fuzz_pack/v2_phase.pack" ph.pack
awk '/^end$/ { on = 1; next } on && NF == 9 { print $1, $9 + 1 }' ph.pack >ph.want
expect_num "phase pack: some hydrate grains" "$(awk '$2 == 2' ph.want | wc -l)" ">" 0
packexport --lammps ph.pack 2>/dev/null | awk 'f { print $1, $2 } /^ITEM: ATOMS/ { f = 1 }' >ph.dump
expect_same "--lammps: atom type 1 mineral, 2 hydrate, by id" ph.want ph.dump
packexport --lammps-data ph.pack >ph.data 2>/dev/null
grep -q '^2 atom types$' ph.data && pass "--lammps-data: 2 atom types with the phase column" || fail "--lammps-data: 2 atom types" "$(grep 'atom types' ph.data)"
awk 'f && NF == 7 { print $1, $2 } /^Atoms/ { f = 1 }' ph.data >ph.dat
expect_same "--lammps-data: atom type 1 mineral, 2 hydrate, by id" ph.want ph.dat
packexport --vtk ph.pack 2>/dev/null | awk '/Name="phase"/ { f = 1; next } f && /<\/DataArray>/ { exit } f { print }' >ph.vtk
awk '{ print $2 - 1 }' ph.want >ph.vwant
expect_same "--vtk: a phase array, 0 mineral, 1 hydrate, in pack order" ph.vwant ph.vtk
packexport --lammps in.pack 2>/dev/null | grep -q '^ITEM: ATOMS id type x y z radius$' && ! packexport --vtk in.pack 2>/dev/null | grep -q phase &&
    pass "no phase column: no phase array, type 1" || fail "no phase column: no phase array" "phase written"

# --- the tables --tsv-grains and --tsv-contacts, and the picture drawn from them ---------------
# on the small dense pack: a row per grain and per contact, the contact counts agree with
# packinfo's, the second end of a grain pair is that grain's centre, and packpic.sh draws a PNG
small_pack dense
expect_ok "--tsv-grains" packexport --tsv-grains -o g.tsv dense.pack
expect_ok "--tsv-contacts" packexport --tsv-contacts -o c.tsv dense.pack
packinfo dense.pack >d.info
expect_num "--tsv-grains: a row per grain" "$(rows g.tsv | wc -l)" "==" "$(info_value d.info grains)"
expect_num "--tsv-contacts: a row per contact (grain pairs and walls)" "$(rows c.tsv | wc -l)" "==" \
    "$(($(info_value d.info contacts_gg) + $(info_value d.info contacts_gw)))"
expect_num "the grains' contacts sum to 2 pairs + walls" "$(sh "$TOP/pipelines/cols.sh" g.tsv contacts | awk '{ s += $1 } END { print s }')" "==" \
    "$((2 * $(info_value d.info contacts_gg) + $(info_value d.info contacts_gw)))"
bad=$(awk -F '\t' 'FNR == NR { if (!/^#/) { x[$1] = $2; y[$1] = $3; z[$1] = $4 }; next }
	/^#/ || $2 < 0 { next }
	{ for (a = 0; a < 3; a++) { v = (a == 0 ? x[$2] : a == 1 ? y[$2] : z[$2]); d = $(6 + a) - v; if (d < 0) d = -d; if (d > 1e-12 * (v < 0 ? -v : v) + 1e-18) n++ } }
	END { print n + 0 }' g.tsv c.tsv)
expect_num "--tsv-contacts: the second end of a pair is the second grain's centre (to 1e-12)" "$bad" "==" 0
expect_num "--tsv-contacts: the normal forces are positive" "$(sh "$TOP/pipelines/cols.sh" c.tsv normal_force | awk '$1 <= 0 { n++ } END { print n + 0 }')" "==" 0
if command -v gnuplot >/dev/null 2>&1; then
	if BIN="$BIN" sh "$TOP/share/plot/packpic.sh" dense.pack pic.png contacts >pic.out 2>&1 && head -c 8 pic.png | od -c | grep -q 'P   N   G'; then
		pass "packpic.sh draws a PNG"
	else
		fail "packpic.sh draws a PNG" "$(head -c 300 pic.out)"
	fi
fi
# spheroplates: --tsv-grains gives side and the unit face normal instead of sphere contacts,
# --tsv-contacts is refused (the plates' interactions are the plate engine's)
packgen --shape spheroplate --platyness 0.5 -n 27 --seed 1 -o pl.pack 2>/dev/null
expect_ok "--tsv-grains of spheroplates" packexport --tsv-grains -o pl.tsv pl.pack
expect_num "plates: unit face normals (|n| - 1 < 1e-12)" "$(sh "$TOP/pipelines/cols.sh" pl.tsv nx ny nz | awk '{ d = sqrt($1 * $1 + $2 * $2 + $3 * $3) - 1; if (d < 0) d = -d; if (d > m) m = d } END { printf "%.3g", m }')" "<" 1e-12
expect_error "--tsv-contacts of spheroplates refused" 1 '^packexport: pl\.pack: grain 1 is a spheroplate \(side > 0\); --tsv-contacts handles spheres only' packexport --tsv-contacts pl.pack
if command -v gnuplot >/dev/null 2>&1; then
	BIN="$BIN" sh "$TOP/share/plot/packpic.sh" pl.pack plpic.png >plpic.out 2>&1 && head -c 8 plpic.png | od -c | grep -q 'P   N   G' &&
	    pass "packpic.sh draws spheroplates" || fail "packpic.sh draws spheroplates" "$(head -c 300 plpic.out)"
fi
