#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
#SBATCH --job-name=qusgm-densify
#SBATCH --time=4:00:00
#SBATCH --nodes=1 --ntasks=1 --cpus-per-task=4
#SBATCH --requeue --open-mode=append
# densify-job.sh DENSIFY-ARGS...: a densify longer than any job may run, as one Slurm job that
# goes on in its own time (pipelines/README.md, "On a Slurm cluster"; densify(1), --checkpoint):
#
#     sbatch pipelines/densify-job.sh --stress 4e6 --checkpoint dense.ck --log dense.tsv \
#         -o dense.pack.gz loose.pack.gz
#     sbatch --dependency=afterok:JOBID next-stage.sh
#
# Run from the directory of the packs, on a file system every node sees.  densify is given
# --time-limit: the job's own limit less QUSGM_MARGIN seconds (default 300) unless the
# arguments give one.  When densify stops for time (exit status 75) the job requeues itself
# (scontrol requeue: the same job id, so that afterok dependencies wait for the end of the
# whole run) and the next run goes on from the checkpoint; where the cluster refuses a requeue
# a copy of this job is submitted instead (sbatch, the same arguments, after this one).  The
# job exits with densify's own status: 0 marks it COMPLETED (afterok fires), anything else
# FAILED.  DENSIFY names the program (default: densify on PATH).
densify=${DENSIFY:-densify}
margin=${QUSGM_MARGIN:-300}
case " $* " in
*" --time-limit"*) ;;
*)	# the job's limit (squeue's %L: the time left, [days-]hours:minutes:seconds)
	left=$(squeue -h -j "${SLURM_JOB_ID:-0}" -o %L 2>/dev/null | awk -F '[-:]' '
		NF == 4 { print (($1 * 24 + $2) * 60 + $3) * 60 + $4; exit }
		NF == 3 { print ($1 * 60 + $2) * 60 + $3; exit }
		NF == 2 { print $1 * 60 + $2; exit }')
	if [ -n "$left" ] && [ "$left" -gt $((margin + 60)) ]; then
		set -- --time-limit $((left - margin)) "$@"
	fi ;;
esac
"$densify" "$@"
st=$?
if [ $st -eq 75 ] && [ -n "${SLURM_JOB_ID:-}" ]; then
	echo "densify-job.sh: stopped for time; the job goes on (requeue of job $SLURM_JOB_ID)" >&2
	scontrol requeue "$SLURM_JOB_ID" && sleep 600	# requeued: Slurm ends this run
	echo "densify-job.sh: requeue refused; submitting a copy after this job" >&2
	sbatch --dependency=afterany:"$SLURM_JOB_ID" ${SLURM_JOB_PARTITION:+--partition="$SLURM_JOB_PARTITION"} \
		${SLURM_JOB_ACCOUNT:+--account="$SLURM_JOB_ACCOUNT"} ${SLURM_CPUS_PER_TASK:+--cpus-per-task="$SLURM_CPUS_PER_TASK"} \
		"$0" "$@" >&2
fi
exit $st
