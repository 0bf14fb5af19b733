# SPDX-License-Identifier: GPL-3.0-or-later
# Signals during an atomic .gz output (issue 19): a tool killed by TERM while it compresses
# leaves neither the target nor a temporary file (.NAME.XXXXXX, .NAME.XXXXXX.z); a signal that
# was ignored at start (nohup: HUP; `cmd &` in a non-interactive shell: INT) stays ignored and
# the tool finishes.  Deterministic: the kill is sent once the compressed temporary exists.
. "$TOP/tests/tools/lib.sh"

# 125000 spheres on a grid: a 12 MB pack whose compression takes a few tenths of a second.
awk 'BEGIN { n = 50; for (i = 0; i < n; i++) for (j = 0; j < n; j++) for (k = 0; k < n; k++)
	printf "%.6e %.6e %.6e 1e-4\n", (i + 0.5) * 2.1e-4, (j + 0.5) * 2.1e-4, (k + 0.5) * 2.1e-4 }' >big.xyzr

# start_in_gzip SIG IGNORED: packimport -o big.pack.gz in the background (with SIG ignored
# when IGNORED is 1), then SIG once .big.pack.gz.XXXXXX.z appears; sets $seen (1: it was sent
# during the compression) and $rc (the exit status).
start_in_gzip() {
	rm -f big.pack.gz .big.pack.gz.*
	if [ "$2" = 1 ]; then
		(trap '' "$1"; exec packimport -q -o big.pack.gz big.xyzr) &
	else	# a shell starts `cmd &` with INT ignored: env resets it (GNU coreutils)
		env --default-signal="$1" packimport -q -o big.pack.gz big.xyzr &
	fi
	pid=$!
	seen=0 i=0
	while [ $i -lt 3000 ] && kill -0 $pid 2>/dev/null; do
		if ls .big.pack.gz.*.z >/dev/null 2>&1; then
			kill -"$1" $pid
			seen=1
			break
		fi
		sleep 0.01
		i=$((i + 1))
	done
	wait $pid
	rc=$?
}

leftovers() { ls -a | grep '^\.big\.pack\.gz\.' | tr '\n' ' '; }

for sig in TERM INT HUP; do
	start_in_gzip $sig 0
	if [ $seen -ne 1 ]; then
		fail "$sig during gzip" "the compressed temporary never appeared (exit $rc)"
		continue
	fi
	left=$(leftovers)
	if [ $rc -lt 128 ]; then
		fail "$sig during gzip kills" "exit $rc"
	elif [ -n "$left" ]; then
		fail "$sig during gzip leaves no temporary" "left: $left"
	elif [ -e big.pack.gz ]; then
		fail "$sig during gzip leaves no target" "big.pack.gz exists"
	else
		pass "$sig during gzip: killed, no target, no temporary"
	fi
done

for sig in HUP INT; do
	start_in_gzip $sig 1
	left=$(leftovers)
	if [ $seen -ne 1 ]; then
		fail "$sig ignored at start" "the compressed temporary never appeared (exit $rc)"
	elif [ $rc -ne 0 ]; then
		fail "$sig ignored at start stays ignored" "exit $rc"
	elif [ -n "$left" ]; then
		fail "$sig ignored at start: no temporary" "left: $left"
	elif ! packinfo big.pack.gz >info.txt 2>info.err; then
		fail "$sig ignored at start: complete output" "packinfo: $(head -c 200 info.err)"
	else
		expect_num "$sig ignored at start stays ignored: complete output, grains" "$(info_value info.txt grains)" == 125000
	fi
done

# Logs are kept (fileio.h, file_log_open): densify killed by TERM, INT or HUP once its log has
# two rows leaves the log with every row written so far, each complete, the first rows of an
# undisturbed run's (the elapsed seconds aside).
packgen -q -n 300 --seed 3 -o lg.pack
densify -q --threads 1 --stress 4e6 --log ref.tsv -o ref.pack lg.pack
cut -f 1-10 ref.tsv >ref.stages
for sig in TERM INT HUP; do
	rm -f k.tsv k.pack
	env --default-signal="$sig" densify -q --threads 1 --stress 4e6 --log k.tsv -o k.pack lg.pack &
	pid=$!
	seen=0 i=0
	while [ $i -lt 3000 ] && kill -0 $pid 2>/dev/null; do
		seen=$(grep -vc '^#' k.tsv 2>/dev/null)
		[ "${seen:-0}" -ge 2 ] && { kill -"$sig" $pid; break; }
		sleep 0.01
		i=$((i + 1))
	done
	wait $pid
	rc=$?
	n=$(grep -vc '^#' k.tsv 2>/dev/null)
	cut -f 1-10 k.tsv >k.stages 2>/dev/null
	if [ "${seen:-0}" -lt 2 ] || [ $rc -lt 128 ]; then
		fail "$sig: densify killed with its log at 2 rows" "rows seen ${seen:-0}, exit $rc"
	elif [ -e k.pack ] || ls -a | grep -q '^\.k\.'; then
		fail "$sig: no pack, no temporary" "$(ls -a | tr '\n' ' ')"
	elif [ "$n" -ge "$seen" ] && [ "$(tail -c 1 k.tsv | od -An -c | tr -d ' ')" = '\n' ] &&
	    [ "$(head -n $((n + 1)) ref.stages)" = "$(cat k.stages)" ]; then
		pass "$sig: the log kept, $n rows (at least the $seen seen before the kill), the undisturbed run's"
	else
		fail "$sig: the log kept with every row so far" "$n rows, $seen seen; $(tail -n 1 k.tsv | cut -c 1-80)"
	fi
done
