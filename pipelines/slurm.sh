#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# slurm.sh CMD [ARG...]: run CMD as one Slurm task, the launcher of the studies' tool runs
# (make -C pipelines SLURM=1, pipelines/README.md "On a Slurm cluster").
#
# Inside an allocation (salloc or sbatch: SLURM_JOB_ID is set) CMD is a job step of it, given
# only the resources it asks for (--exact), so that make -j runs steps side by side and
# queues the rest in the allocation; outside one it is a job of its own, submitted with
# srun to QUSGM_JOB_PARTITION under QUSGM_JOB_ACCOUNT with a limit of QUSGM_JOB_TIME.
# srun waits for CMD and exits with its status, so make sees a failed step as a failed recipe.
#
# The resources come from the environment, set once by pipelines/Makefile (JOB_CPUS,
# JOB_MEM, JOB_TIME, JOB_PARTITION, JOB_ACCOUNT, JOB_FLAGS): not SLURM_* or SRUN_* names,
# which srun itself reads.
cpus=${QUSGM_JOB_CPUS:-1}
mem=${QUSGM_JOB_MEM:-2G}
time=${QUSGM_JOB_TIME:-1:00:00}
[ $# -gt 0 ] || { echo "usage: slurm.sh CMD [ARG...]" >&2; exit 2; }
command -v srun >/dev/null 2>&1 || { echo "slurm.sh: srun not found (is this a Slurm login node?)" >&2; exit 127; }

# the job's or step's name: the tool (timed.sh's CMD is its fourth word)
name=qusgm
if [ "$(basename -- "$1")" = sh ] && [ "$(basename -- "${2:-}")" = timed.sh ] && [ $# -ge 6 ]; then
	name=qusgm-$(basename -- "$6")
else
	name=qusgm-$(basename -- "$1")
fi

if [ -n "${SLURM_JOB_ID:-}" ]; then
	# a job step: the allocation's partition, account and limit apply
	# shellcheck disable=SC2086
	exec srun --quiet --exact --nodes=1 --ntasks=1 --cpus-per-task="$cpus" --mem="$mem" \
		--time="$time" --job-name="$name" ${QUSGM_JOB_FLAGS:-} -- "$@"
fi
# a job of its own
set -- --nodes=1 --ntasks=1 --cpus-per-task="$cpus" --mem="$mem" --time="$time" \
	--job-name="$name" -- "$@"
[ -n "${QUSGM_JOB_ACCOUNT:-}" ] && set -- --account="$QUSGM_JOB_ACCOUNT" "$@"
[ -n "${QUSGM_JOB_PARTITION:-}" ] && set -- --partition="$QUSGM_JOB_PARTITION" "$@"
# shellcheck disable=SC2086
exec srun --quiet ${QUSGM_JOB_FLAGS:-} "$@"
