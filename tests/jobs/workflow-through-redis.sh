#!/usr/bin/env bash
# The planning workflow test (tests/server/PlanningWorkflowTest.cpp) passes unchanged
# through Redis with two worker processes. A real redis-server on a free port, two `orthosim
# worker` processes on the test data folder, and every test server started with --redis
# (tests/server/ServerProcess reads ORTHOSIM_TEST_REDIS). Passes when the tests pass and the
# fine job ran on one of the workers. Exit 77 (skipped) without redis-server, unless CI=true.
# Usage: workflow-through-redis.sh ORTHOSIM_CLI ORTHOSIM_TESTS DATA_DIR LOG_DIR
set -euo pipefail
cli=$1 tests=$2 data=$3 logs=$4
if ! command -v redis-server >/dev/null; then
  if [ "${CI:-}" = true ]; then echo "redis-server is not on PATH (CI=true: scripts/setup-deps.sh installs it)"; exit 1; fi
  echo "redis-server is not on PATH: apt-get install redis-server (scripts/setup-deps.sh); skipped"
  exit 77
fi
mkdir -p "$logs" "$data"
work=$(mktemp -d)
pids=()
cleanup() {
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill -9 "${pids[i]}" 2>/dev/null || true; done  # workers, then Redis
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

# A free port: redis-server refuses a taken one; try a few.
port=""
for _ in 1 2 3 4 5; do
  candidate=$((20000 + RANDOM % 30000))
  redis-server --port "$candidate" --bind 127.0.0.1 --dir "$work" --save '' --appendonly no \
    --logfile "$logs/workflow-redis.log" &
  pid=$!
  for _ in $(seq 50); do
    if redis-cli -p "$candidate" ping 2>/dev/null | grep -q PONG; then port=$candidate; break; fi
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  if [ -n "$port" ]; then pids+=("$pid"); break; fi
  kill -9 "$pid" 2>/dev/null || true
done
[ -n "$port" ] || { echo "redis-server did not start (see $logs/workflow-redis.log)"; exit 1; }
url="redis://127.0.0.1:$port"

for w in 1 2; do
  out="$work/worker-$w.out"
  "$cli" worker --redis "$url" --data "$data" --name "workflow-w$w" >"$out" 2>"$logs/workflow-w$w.log" &
  pids+=("$!")
  for _ in $(seq 300); do grep -q "worker ready" "$out" 2>/dev/null && break; sleep 0.1; done
  grep -q "worker ready" "$out" || { echo "worker $w did not start:"; cat "$logs/workflow-w$w.log"; exit 1; }
done

ORTHOSIM_TEST_REDIS="$url" "$tests" --gtest_filter='PlanningWorkflow.*'

done_jobs=$(cat "$logs"/workflow-w[12].log | grep -c ' done$' || true)
echo "fine jobs done on the workers: $done_jobs"
[ "$done_jobs" -ge 1 ] || { echo "no fine job ran on a worker: were the servers started with --redis?"; exit 1; }
