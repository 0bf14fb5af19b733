#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# tests/cluster-check.sh BIN: make cluster-check.  Sets up Debian's slurm-wlm as a one-node
# cluster on this machine (a private munged, slurmctld and slurmd, their configuration, keys,
# sockets, state and logs in tests/out/cluster-check, on ports of their own), runs a small
# study through it with every tool run a Slurm job step (make -C pipelines SLURM=1 inside
# salloc), runs the same study with plain make -j, compares every file of the two byte for
# byte, counts the job steps in slurmd's log, runs densify as the self-continuing batch job
# pipelines/densify-job.sh with an afterok dependency on it, and stops the daemons it started.
# As root it installs slurm-wlm and munge with apt-get when missing; otherwise it needs them.
# Nothing outside this machine.  Ends "N passed, N failed".
BIN=${1:-build/bin}
case $BIN in /*) ;; *) BIN=$(pwd)/$BIN ;; esac
STUDY=${CLUSTER_STUDY:-fig4}
J=${CLUSTER_J:-2}
D=$(pwd)/tests/out/cluster-check
pass=0 fail=0
ok() { echo "PASS: $1"; pass=$((pass + 1)); }
ko() { echo "FAIL: $1"; fail=$((fail + 1)); }
finish() { echo "$pass passed, $fail failed"; [ "$fail" -eq 0 ]; exit; }

APT="DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge"
need() { command -v slurmctld >/dev/null 2>&1 && command -v slurmd >/dev/null 2>&1 &&
	command -v srun >/dev/null 2>&1 && command -v munged >/dev/null 2>&1; }
if ! need; then
	if [ "$(id -u)" -ne 0 ]; then
		echo "cluster-check: slurm-wlm and munge are not installed; as root: $APT" >&2
		exit 1
	fi
	echo "cluster-check: installing slurm-wlm and munge: $APT"
	env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null ||
		{ echo "cluster-check: apt-get failed" >&2; exit 1; }
fi
[ "$(id -u)" -eq 0 ] || { echo "cluster-check: run as root (slurmd starts job steps as their user)" >&2; exit 1; }
t0=$(date +%s)

# --- the cluster -------------------------------------------------------------------------
rm -rf "$D"
mkdir -p "$D/munge" "$D/spool" "$D/state" "$D/out"
chmod 700 "$D/munge"
pids=
stop() {
	for p in $pids; do kill "$p" 2>/dev/null; done
	for p in $pids; do
		i=0
		while kill -0 "$p" 2>/dev/null && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
		kill -9 "$p" 2>/dev/null
	done
	pids=
}
trap 'stop' EXIT
trap 'stop; exit 1' INT TERM HUP

# a munge key of its own (the system's /etc/munge is not touched)
dd if=/dev/urandom of="$D/munge/munge.key" bs=1024 count=1 2>/dev/null
chmod 400 "$D/munge/munge.key"
munged --force --foreground --key-file="$D/munge/munge.key" --socket="$D/munge/munge.socket" \
	--pid-file="$D/munge/munged.pid" --log-file="$D/munge/munged.log" \
	--seed-file="$D/munge/munged.seed" >"$D/munge/munged.out" 2>&1 &
pids="$pids $!"

host=$(hostname -s)
cpus=$(nproc)
mem=$(awk '/^MemTotal:/ { m = int($2 / 1024) - 1024; print (m < 1024 ? 1024 : m) }' /proc/meminfo)
cat >"$D/slurm.conf" <<EOF
# written by tests/cluster-check.sh: a one-node cluster for make cluster-check
ClusterName=qusgm-check
SlurmctldHost=$host
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$D/munge/munge.socket
CredType=cred/munge
SlurmctldPidFile=$D/slurmctld.pid
SlurmdPidFile=$D/slurmd.pid
SlurmctldLogFile=$D/slurmctld.log
SlurmdLogFile=$D/slurmd.log
SlurmdDebug=info
SlurmctldDebug=info
SlurmdSpoolDir=$D/spool
StateSaveLocation=$D/state
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU_Memory
ReturnToService=2
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=check Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$D/slurm.conf"
# the allocation's and the steps' memory (JOB_MEM, the steps run two at a time)
unset SLURM_JOB_ID

i=0
while [ ! -S "$D/munge/munge.socket" ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
if [ -S "$D/munge/munge.socket" ]; then ok "munged runs (its own key and socket)"
else ko "munged did not start:"; cat "$D/munge/munged.out" "$D/munge/munged.log" 2>/dev/null | tail -n 5; finish; fi

slurmctld -D -f "$D/slurm.conf" >"$D/slurmctld.out" 2>&1 &
pids="$pids $!"
slurmd -D -f "$D/slurm.conf" >"$D/slurmd.out" 2>&1 &
pids="$pids $!"
i=0 state=
while [ $i -lt 60 ]; do
	state=$(sinfo -h -N -n "$host" -o %t 2>/dev/null)
	[ "$state" = idle ] && break
	sleep 1; i=$((i + 1))
done
if [ "$state" = idle ]; then ok "slurmctld and slurmd run: node $host idle in partition check ($cpus CPUs, $mem MB)"
else
	ko "node $host not idle after 60 s (sinfo: '$state')"
	tail -n 8 "$D/slurmctld.log" "$D/slurmd.log" "$D/slurmctld.out" "$D/slurmd.out" 2>/dev/null
	finish
fi

# --- the study, through Slurm and here -----------------------------------------------------
# both runs write to the same OUT, moved aside after each: the packs' history records their
# commands, paths included, so only the same path gives the same bytes
O=$D/out/run
s0=$(date +%s)
salloc --quiet -N1 -c"$J" --mem=$((J * 600))M -J qusgm-check \
	sh pipelines/study-salloc.sh JOB_MEM=500M JOB_TIME=0:30:00 \
	BIN="$BIN" SMALL=1 OUT="$O" "$STUDY" >"$D/slurm-make.log" 2>&1
rc=$?
mv "$O" "$D/out/slurm"
s1=$(date +%s)
if [ $rc -eq 0 ]; then ok "salloc -N1 -c$J sh pipelines/study-salloc.sh SMALL=1 $STUDY ($((s1 - s0)) s)"
else ko "salloc make -C pipelines SLURM=1 SMALL=1 -j$J $STUDY exited $rc:"; tail -n 15 "$D/slurm-make.log"; fi

make --no-print-directory -C pipelines BIN="$BIN" SMALL=1 OUT="$O" -j"$J" "$STUDY" \
	>"$D/local-make.log" 2>&1
rc=$?
mv "$O" "$D/out/local"
s2=$(date +%s)
if [ $rc -eq 0 ]; then ok "make -C pipelines SMALL=1 -j$J $STUDY ($((s2 - s1)) s)"
else ko "make -C pipelines SMALL=1 -j$J $STUDY exited $rc:"; tail -n 15 "$D/local-make.log"; fi

# every file of the two, byte for byte: times.tsv (seconds) aside, report.md without its
# Cost line (the seconds), and the logs without their elapsed[s] column
(cd "$D/out/local" && find . -type f | sort) >"$D/files.local"
(cd "$D/out/slurm" && find . -type f | sort) >"$D/files.slurm"
if cmp -s "$D/files.local" "$D/files.slurm" && [ -s "$D/files.local" ]; then
	ok "the same $(wc -l <"$D/files.local") files in both runs"
else
	ko "the two runs wrote different files:"; diff "$D/files.local" "$D/files.slurm" | head
fi
same=0 differ=0
while read -r f; do
	[ -f "$D/out/slurm/$f" ] || continue
	case $f in
	./times.tsv) continue ;;
	*/report.md)
		grep -v '^Cost:' "$D/out/local/$f" >"$D/a"
		grep -v '^Cost:' "$D/out/slurm/$f" >"$D/b"
		cmp -s "$D/a" "$D/b" ;;
	*.tsv)	# a log's elapsed[s] (its last column) is the one value that differs between runs
		if head -n 1 "$D/out/local/$f" | grep -q "$(printf '\telapsed\\[s\\]$')"; then
			awk -F '\t' -v OFS='\t' '{ NF--; print }' "$D/out/local/$f" >"$D/a"
			awk -F '\t' -v OFS='\t' '{ NF--; print }' "$D/out/slurm/$f" >"$D/b"
			cmp -s "$D/a" "$D/b"
		else cmp -s "$D/out/local/$f" "$D/out/slurm/$f"; fi ;;
	*) cmp -s "$D/out/local/$f" "$D/out/slurm/$f" ;;
	esac
	if [ $? -eq 0 ]; then same=$((same + 1)); else differ=$((differ + 1)); echo "  differs: $f"; fi
done <"$D/files.local"
if [ $differ -eq 0 ] && [ $same -gt 0 ]; then ok "$same files byte for byte identical (times.tsv aside; report.md without its Cost line, logs without elapsed[s])"
else ko "$differ files differ, $same identical"; fi

# one job step per tool run: timed.sh logs one line per tool run to times.tsv, slurmd one
# "launch task" per step it started (the allocation's own job has none: salloc runs make here)
runs=$(wc -l <"$D/out/local/times.tsv")
sruns=$(wc -l <"$D/out/slurm/times.tsv")
steps=$(grep -c 'launch task' "$D/slurmd.log")
if [ "$steps" -eq "$runs" ] && [ "$sruns" -eq "$runs" ] && [ "$runs" -gt 0 ]; then
	ok "$steps Slurm job steps for $runs tool runs (slurmd.log)"
else ko "$steps job steps in slurmd.log, $sruns tool runs through Slurm, $runs here"; fi
grep 'launch task' "$D/slurmd.log" | sed 's/^/  /'

# a failing tool run is a failing step, and make sees its status
salloc --quiet -N1 -c1 --mem=600M -J qusgm-check-fail env QUSGM_JOB_MEM=500M sh pipelines/slurm.sh sh -c 'exit 3' >"$D/fail.log" 2>&1
rc=$?
if [ $rc -eq 3 ]; then ok "a step that exits 3 makes slurm.sh exit 3"; else ko "a step that exits 3: slurm.sh exited $rc"; cat "$D/fail.log"; fi

# outside an allocation each tool run is a job of its own (srun -p check -t ...): the stages
# of the study's first pack, made again that way, the same bytes as make -j's
first=$(sed -n 1p "$D/out/local/times.tsv" | cut -f1)
case $first in "$O"/*) rel=${first#"$O"/} ;; *) rel= ;; esac
jobs0=$(grep -c '_slurm_rpc_allocate_resources JobId=' "$D/slurmctld.log")
if [ -n "$rel" ] && make --no-print-directory -C pipelines SLURM=1 JOB_PARTITION=check JOB_MEM=500M \
	JOB_TIME=0:10:00 BIN="$BIN" SMALL=1 OUT="$O" "$first" >"$D/jobs-make.log" 2>&1; then
	n=$(wc -l <"$O/times.tsv")
	jobs=$(($(grep -c '_slurm_rpc_allocate_resources JobId=' "$D/slurmctld.log") - jobs0))
	bad=0
	for f in $(cut -f1 "$O/times.tsv"); do cmp -s "$f" "$D/out/local/${f#"$O"/}" || { bad=1; echo "  differs: $f"; }; done
	if [ $bad -eq 0 ] && [ "$jobs" -eq "$n" ]; then ok "without salloc: $rel and what it needs as $jobs Slurm jobs of their own, the same bytes"
	else ko "without salloc: $jobs jobs for $n tool runs, outputs differ: $bad"; fi
else ko "without salloc: make $rel failed"; tail -n 10 "$D/jobs-make.log"; fi
rm -rf "$O"

# densify's job that goes on in its own time (pipelines/densify-job.sh): a 300-grain densify
# with --time-limit 2 stops for time, requeues itself and goes on from its checkpoint until it
# ends; the job ends COMPLETED, a job submitted with afterok on it runs, and the pack is the
# uninterrupted run's (history lines aside: they record the options)
C=$D/chain
rm -rf "$C" && mkdir -p "$C"
top=$(pwd)
if (cd "$C" && "$BIN/packgen" -q -n 300 --seed 3 -o loose.pack && "$BIN/densify" -q --stress 4e6 --log ref.tsv -o ref.pack loose.pack) &&
    jid=$(cd "$C" && sbatch --parsable -c1 --mem=500M -t 0:20:00 -o chain.out --export=ALL,DENSIFY="$BIN/densify" \
	"$top/pipelines/densify-job.sh" -q --stress 4e6 --checkpoint d.ck --time-limit 2 --log d.tsv -o d.pack loose.pack) &&
    dep=$(cd "$C" && sbatch --parsable -c1 --mem=100M -t 0:05:00 -o dep.out --dependency=afterok:"$jid" --wrap 'echo fired >fired'); then
	# Slurm holds a requeued job for about 2 minutes (Reason=BeginTime): released at once here
	i=0
	while [ $i -lt 600 ] && squeue -h -j "$jid,$dep" 2>/dev/null | grep -q .; do
		squeue -h -j "$jid" -o %r 2>/dev/null | grep -q BeginTime && scontrol update jobid="$jid" StartTime=now 2>/dev/null
		sleep 1; i=$((i + 1))
	done
	js=$(scontrol show job "$jid" 2>/dev/null | tr ' ' '\n' | sed -n 's/^JobState=//p; s/^Restarts=/restarts /p; s/^ExitCode=/exit /p' | tr '\n' ' ')
	ds=$(scontrol show job "$dep" 2>/dev/null | tr ' ' '\n' | sed -n 's/^JobState=//p')
	echo "  densify-job.sh job $jid: $js($i s); afterok job $dep: $ds"
	case $js in
	"COMPLETED restarts "[1-9]*" exit 0:0 ") ok "densify-job.sh: stopped for time, requeued, went on, ended COMPLETED (exit 0)" ;;
	*) ko "densify-job.sh: job state $js"; tail -n 5 "$C/chain.out" ;;
	esac
	if [ "$ds" = COMPLETED ] && [ -f "$C/fired" ]; then ok "an afterok dependency on it ran"; else ko "the afterok dependency: state '$ds'"; fi
	grep -v '^history densify ' "$C/ref.pack" >"$C/ref.body"
	grep -v '^history densify ' "$C/d.pack" >"$C/d.body" 2>/dev/null
	cut -f 1-10 "$C/ref.tsv" >"$C/ref.stages"
	cut -f 1-10 "$C/d.tsv" >"$C/d.stages" 2>/dev/null
	if cmp -s "$C/ref.body" "$C/d.body" && cmp -s "$C/ref.stages" "$C/d.stages"; then
		ok "densify-job.sh: the pack and the log (elapsed aside) are the uninterrupted run's"
	else ko "densify-job.sh: the pack or the log differs from the uninterrupted run's"; fi
else ko "densify-job.sh: could not make the inputs or submit"; fi

stop
sleep 0.5
left=
for f in "$D/slurmctld.pid" "$D/slurmd.pid" "$D/munge/munged.pid"; do
	[ -s "$f" ] && kill -0 "$(cat "$f")" 2>/dev/null && left="$left $(cat "$f")"
done
if [ -z "$left" ]; then ok "daemons stopped"; else ko "still running:$left"; fi
echo "cluster-check: $(($(date +%s) - t0)) s in all; logs and both runs in $D"
finish
