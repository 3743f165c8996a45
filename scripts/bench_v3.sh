#!/usr/bin/env bash
# Times Box2D v3's benchmark scenes (v3_*: v3.1.1's seven, master's washer and compounds) for
# impulse2d and Box2D v3 at 1 and 2 threads, alternately (each scene's rows round robin, --repeats
# times), and writes the CSV and the markdown table of docs/benchmarks.md's v3 section. It only
# runs impulse2d_bench, which must have been built with IMPULSE2D_BENCH_BOX2D_V3_DIR pointing at
# a v3 build (docs/benchmarks.md); it never builds v3.
#
#   scripts/bench_v3.sh [--bench PATH] [--csv FILE] [--repeats N] [--threads 1,2]
#                       [--solvers substep,default] [-- ARGS...]
#
# --solvers picks the rows: impulse2d's default solver (substep) and v3's only one (default).
# ARGS go to impulse2d_bench as they are (e.g. --also substep:4:3 for more impulse2d rows).
set -euo pipefail
REPO="$(cd "$(dirname "$0")/.." && pwd)"
WS="${IMPULSE2D_WS:-${XDG_CACHE_HOME:-$HOME/.cache}/impulse2d_ws}"
BENCH="$WS/devel/lib/impulse2d/impulse2d_bench"
CSV="bench_v3.csv"
REPEATS=5
THREADS="1,2"
SOLVERS="substep,default"
while [ $# -gt 0 ]; do
  case "$1" in
    --bench) BENCH="$2"; shift 2 ;;
    --csv) CSV="$2"; shift 2 ;;
    --repeats) REPEATS="$2"; shift 2 ;;
    --threads) THREADS="$2"; shift 2 ;;
    --solvers) SOLVERS="$2"; shift 2 ;;
    --) shift; break ;;
    -h|--help) sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "bench_v3.sh: unknown argument '$1' (--help for usage)" >&2; exit 2 ;;
  esac
done
if [ ! -x "$BENCH" ]; then
  echo "bench_v3.sh: no impulse2d_bench at $BENCH (--bench PATH, or IMPULSE2D_WS)" >&2
  exit 2
fi
# The engine list tells whether box2d_v3 was compiled in: refuse rather than time impulse2d alone.
if ! "$BENCH" --quick --scenes v3_smash --engines box2d_v3 --csv /dev/null >/dev/null 2>&1; then
  echo "bench_v3.sh: $BENCH has no box2d_v3 engine; build it with" >&2
  echo "  -DIMPULSE2D_BENCH_BOX2D_V3_DIR=<a Box2D v3 build or install> (docs/benchmarks.md)" >&2
  exit 2
fi
echo "bench_v3.sh: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg) at the start" >&2
"$BENCH" --scenes v3_ --engines impulse2d,box2d_v3 --solvers "$SOLVERS" --threads "$THREADS" \
  --repeats "$REPEATS" --csv "$CSV" "$@"
echo "bench_v3.sh: load $(cut -d' ' -f1-3 /proc/loadavg) at the end" >&2
/usr/bin/python3 "$REPO/scripts/v3_table.py" "$CSV" --out "${CSV%.csv}_table.md"
echo "bench_v3.sh: table in ${CSV%.csv}_table.md" >&2
