#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# study-salloc.sh [MAKE-ARGS...]: a study of pipelines/Makefile inside a Slurm allocation,
# every tool run a job step of it (pipelines/README.md, "On a Slurm cluster"):
#
#     salloc -N1 -c 8 --mem=16G -t 2:00:00 sh pipelines/study-salloc.sh OUT=/scratch/$USER/qusgm all
#
# make runs as many steps side by side as the allocation has CPUs (-j, unless MAKE-ARGS give
# one), each step given JOB_MEM (default: the allocation's memory over -j).  Exits with make's
# status.  Run from the top directory of the sources.
[ -n "${SLURM_JOB_ID:-}" ] || { echo "study-salloc.sh: not inside an allocation (run it under salloc or sbatch)" >&2; exit 2; }
dir=$(cd "$(dirname "$0")" && pwd)
j=${SLURM_CPUS_ON_NODE:-1}
case " $* " in *" -j"*) j= ;; esac
mem=
if [ -n "$j" ] && [ -n "${SLURM_MEM_PER_NODE:-}" ]; then
	mem="JOB_MEM=$((SLURM_MEM_PER_NODE / j))M"
fi
exec make --no-print-directory -C "$dir" SLURM=1 ${j:+-j"$j"} $mem "$@"
