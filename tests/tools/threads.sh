# SPDX-License-Identifier: GPL-3.0-or-later
# Threads (lib/base/par.h): every tool that minimises gives the same bytes on one thread and
# on two.  The packs here have 300 grains, under the 4096 at which loops are split by default,
# so QUSGM_PAR_BLOCK=16 cuts them into 19 blocks of 16 grains, and two threads take 9 and 10
# blocks: every gather across the threads' boundary (functional.c's hertz_gather, the friction
# term's columns, the DEM's crossing pairs in packgen) and every blocked dot product runs.  The packs may differ only in the
# history line's --threads=N; the tables not at all.  Without OpenMP (OMPFLAGS=) both runs are
# one thread and the comparisons hold trivially: the first check says which it is.
. "$TOP/tests/tools/lib.sh"

export QUSGM_PAR_BLOCK=16
# two-thread runs beside make check's other job oversubscribe the two cores: threads that
# sleep at a barrier instead of spinning keep that from tripling the time (the bytes do not
# depend on it)
export OMP_WAIT_POLICY=passive
# packgen on one thread and on two; the one-thread pack is the others' input (a third run
# with OMP_NUM_THREADS=1 made the same pack again)
# (the sanitizer build's pack has 150 grains: still ten blocks of 16 for the threads, at half
# of its 29 s of CPU)
N=300
[ "${BIN#*build-san}" != "$BIN" ] && N=150
for t in 1 2; do
	packgen --threads $t -n $N --seed 7 -o g$t.pack 2>g$t.err
done
cp g1.pack loose.pack
if packinfo --threads 2 -v loose.pack 2>&1 >/dev/null | grep -q '^packinfo: 2 threads'; then
	pass "--threads 2 runs two threads (-v says so)"
else
	fail "--threads 2 runs two threads (-v says so)" "$(packinfo --threads 2 -v loose.pack 2>&1 >/dev/null | head -1)"
fi

# same_pack NAME A B: the same bytes but for the history lines' --threads (as typed and as run)
same_pack() {
	sed 's/ --threads[= ][0-9]*//g' "$2" >"$2.cmp"
	sed 's/ --threads[= ][0-9]*//g' "$3" >"$3.cmp"
	if cmp -s "$2.cmp" "$3.cmp"; then pass "$1"; else fail "$1" "$(cmp "$2.cmp" "$3.cmp" 2>&1 | head -1)"; fi
}

for t in 1 2; do
	densify --threads $t -o d$t.pack loose.pack 2>d$t.err
	frictionalize --threads $t -o f$t.pack d1.pack >f$t.tsv 2>f$t.err
	loadtest --threads $t -n 4 -o l$t.pack f1.pack >l$t.tsv 2>l$t.err
	loadtest --threads $t -n 4 --mu 0 -p isotropic -o i$t.pack d1.pack >i$t.tsv 2>i$t.err
	loadtest --threads $t -n 2 --method fire -o F$t.pack f1.pack >F$t.tsv 2>F$t.err
	loadtest --threads $t -n 2 --method cg --mu 0 -o C$t.pack d1.pack >C$t.tsv 2>C$t.err
	loadtest --threads $t -n 2 --method newton --mu 0 -o N$t.pack d1.pack >N$t.tsv 2>N$t.err
	loadtest --threads $t -n 2 --method newton -o M$t.pack f1.pack >M$t.tsv 2>M$t.err
	packinfo --threads $t --tsv f1.pack >p$t.tsv 2>p$t.err
done
same_pack "packgen (the DEM's force loop): 1 and 2 threads" g1.pack g2.pack
same_pack "densify: 1 and 2 threads" d1.pack d2.pack
same_pack "frictionalize: 1 and 2 threads" f1.pack f2.pack
expect_same "frictionalize: table" f1.tsv f2.tsv
same_pack "loadtest, frictional: 1 and 2 threads" l1.pack l2.pack
expect_same "loadtest, frictional: table" l1.tsv l2.tsv
same_pack "loadtest, frictionless isotropic: 1 and 2 threads" i1.pack i2.pack
expect_same "loadtest, frictionless isotropic: table" i1.tsv i2.tsv
same_pack "loadtest --method fire: 1 and 2 threads" F1.pack F2.pack
expect_same "loadtest --method fire: table" F1.tsv F2.tsv
same_pack "loadtest --method cg: 1 and 2 threads" C1.pack C2.pack
expect_same "loadtest --method cg: table" C1.tsv C2.tsv
same_pack "loadtest --method newton: 1 and 2 threads" N1.pack N2.pack
expect_same "loadtest --method newton: table" N1.tsv N2.tsv
same_pack "loadtest --method newton, frictional: 1 and 2 threads" M1.pack M2.pack
expect_same "loadtest --method newton, frictional: table" M1.tsv M2.tsv
expect_same "packinfo: 1 and 2 threads" p1.tsv p2.tsv
# the runs did something: a table per increment, and the frictional test moved the stress
[ "$(grep -c '^[0-9-]' l1.tsv)" -ge 4 ] && pass "loadtest wrote its increments" || fail "loadtest wrote its increments" "$(wc -l <l1.tsv) lines"
if grep -q ' --threads=2$' d2.pack && grep -q ' --threads=1$' d1.pack; then
	pass "the history records the thread count"
else
	fail "the history records the thread count" "$(grep '^history densify' d2.pack | tail -c 80)"
fi
# OMP_NUM_THREADS is honoured when --threads is not given
OMP_NUM_THREADS=2 packinfo -v loose.pack >/dev/null 2>omp.err
grep -q '^packinfo: 2 threads' omp.err && pass "OMP_NUM_THREADS=2 honoured" || fail "OMP_NUM_THREADS=2 honoured" "$(head -1 omp.err)"
OMP_NUM_THREADS=1 packinfo -v loose.pack >/dev/null 2>omp1.err
grep -q '^packinfo: 1 thread ' omp1.err && pass "OMP_NUM_THREADS=1 honoured" || fail "OMP_NUM_THREADS=1 honoured" "$(head -1 omp1.err)"
expect_error "--threads -1 refused" 2 '^densify: --threads: expected 0' densify --threads -1 loose.pack

# OMP_NUM_THREADS is held to --threads' range (1 to 4096): 100000 failed later as "out of
# memory for the neighbour list" (or a crash), 5000 started 5000 threads
expect_error "OMP_NUM_THREADS=100000 refused, named" 2 "^packinfo: OMP_NUM_THREADS: expected 1 to 4096.*got '100000'" \
	env OMP_NUM_THREADS=100000 packinfo loose.pack
expect_error "OMP_NUM_THREADS=5000 refused" 2 "^densify: OMP_NUM_THREADS: expected 1 to 4096" \
	env OMP_NUM_THREADS=5000 densify -o never.pack loose.pack
# values the runtime cannot read: it warns (its own line), and the tool refuses them
for v in 0 lots; do
	env OMP_NUM_THREADS=$v packinfo loose.pack >bad.out 2>bad.err
	rc=$?
	if [ $rc -eq 2 ] && [ ! -s bad.out ] && grep -q "^packinfo: OMP_NUM_THREADS: expected 1 to 4096.*got '$v'" bad.err; then
		pass "OMP_NUM_THREADS=$v refused"
	else
		fail "OMP_NUM_THREADS=$v refused" "exit $rc: $(head -c 300 bad.err)"
	fi
done
OMP_NUM_THREADS=' 2,1' packinfo -v loose.pack >/dev/null 2>ompl.err
grep -q '^packinfo: 2 threads' ompl.err && pass "OMP_NUM_THREADS=' 2,1' (a list for nested levels): 2 threads" ||
	fail "OMP_NUM_THREADS=' 2,1': 2 threads" "$(head -c 300 ompl.err)"
OMP_NUM_THREADS=100000 packinfo --threads 1 -v loose.pack >/dev/null 2>ompt.err &&
	grep -q '^packinfo: 1 thread ' ompt.err && pass "--threads given: OMP_NUM_THREADS not used, not checked" ||
	fail "--threads given: OMP_NUM_THREADS not used" "$(head -c 300 ompt.err)"

# The wait policy (lib/base/par_start.c): unless the user set one, idle threads sleep at once
# (libgomp's OMP_DISPLAY_ENV shows GOMP_SPINCOUNT '0'), set before libgomp reads it, without
# starting the tool again: the tool keeps its name in ps, runs when started through the
# dynamic loader, and the runtime's warnings come once.
if packinfo --threads 2 -v loose.pack 2>&1 >/dev/null | grep -q '^packinfo: 2 threads'; then
	env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT OMP_DISPLAY_ENV=verbose packinfo --threads 2 loose.pack >/dev/null 2>disp.err
	grep -q "GOMP_SPINCOUNT = '0'" disp.err && pass "idle threads wait passively (GOMP_SPINCOUNT '0')" ||
		fail "idle threads wait passively" "$(grep -E 'SPINCOUNT|WAIT_POLICY' disp.err | tr '\n' ' ')"
	env -u GOMP_SPINCOUNT OMP_WAIT_POLICY=active OMP_DISPLAY_ENV=verbose packinfo --threads 2 loose.pack >/dev/null 2>disp.err
	grep -q "GOMP_SPINCOUNT = '0'" disp.err && fail "OMP_WAIT_POLICY=active kept" "$(grep SPINCOUNT disp.err)" ||
		pass "the user's OMP_WAIT_POLICY=active kept"
	env -u OMP_WAIT_POLICY OMP_PROC_BIND=nonsense packinfo --threads 2 loose.pack >/dev/null 2>warn.err
	expect_num "libgomp's warning printed once" "$(grep -c 'Invalid value for environment variable OMP_PROC_BIND' warn.err)" == 1
fi
# the name in ps: the tool's, while it waits for its input (a FIFO no one writes yet)
rm -f in.fifo
mkfifo in.fifo
env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT packinfo --threads 2 in.fifo >fifo.out 2>fifo.err &
pid=$!
sleep 0.5
name=$(ps -o comm= -p $pid 2>/dev/null || cat /proc/$pid/comm)
cat loose.pack >in.fifo
wait $pid
rc=$?
if [ "$name" = packinfo ] && [ $rc -eq 0 ] && grep -q '^grains' fifo.out; then
	pass "the name in ps is the tool's (packinfo --threads 2)"
else
	fail "the name in ps is the tool's (packinfo --threads 2)" "ps says '$name', exit $rc"
fi
# started through the dynamic loader (it exited 127 or 1: the restart ran the loader with the
# tool's arguments)
loader=$(ldd "$(command -v packinfo)" 2>/dev/null | awk '$1 ~ /^\/.*ld[-.]/ { print $1; exit }')
if [ -z "$loader" ] || [ ! -x "$loader" ]; then
	fail "started through the dynamic loader" "no loader found by ldd"
else
	env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$loader" "$(command -v packinfo)" --threads 2 loose.pack >ld.out 2>ld.err
	rc=$?
	[ $rc -eq 0 ] && grep -q '^grains' ld.out && pass "started through the dynamic loader ($loader) with --threads 2" ||
		fail "started through the dynamic loader with --threads 2" "exit $rc: $(head -c 200 ld.err)"
fi
# an empty argv[0]: the messages name the tool
env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT perl -e 'exec { $ARGV[0] } "", @ARGV[1 .. $#ARGV] or exit 99' \
	"$(command -v packinfo)" --threads 2 no-such.pack >/dev/null 2>argv0.err
grep -q '^packinfo: no-such.pack: ' argv0.err && pass "an empty argv[0]: the messages name the tool" ||
	fail "an empty argv[0]: the messages name the tool" "$(head -c 200 argv0.err)"
