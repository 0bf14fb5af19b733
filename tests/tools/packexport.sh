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
