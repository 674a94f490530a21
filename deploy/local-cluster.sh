#!/usr/bin/env bash
# Runs the service on this host without systemd: a coordinator and N workers, each a background
# process with its pid file and log in one run directory, for trying the service or for tests.
# Usage: deploy/local-cluster.sh start [N] [--insecure] | stop | status
#   N (start only): workers to start, default the number of cores.
#   --insecure (start only): allow endpoints other hosts reach, although CURVE is off.
# Environment: EVOSLAM_RUN_DIR (default run/local-cluster), EVOSLAM_BIN (default build/),
#   EVOSLAM_CLIENTS (default tcp://127.0.0.1:5555), EVOSLAM_WORKERS (default tcp://127.0.0.1:5556),
#   EVOSLAM_STOP_TIMEOUT (seconds stop waits before SIGKILL, default 30).
# Exit status: 0 done; 1 failed; 2 bad arguments; 3 (status) the coordinator is not running.
set -euo pipefail

action=${1:-}
root=$(cd "$(dirname "$0")/.." && pwd)
run_dir=$(realpath -m "${EVOSLAM_RUN_DIR:-$root/run/local-cluster}")
bin=$(realpath -m "${EVOSLAM_BIN:-$root/build}")
clients=${EVOSLAM_CLIENTS:-tcp://127.0.0.1:5555}
workers=${EVOSLAM_WORKERS:-tcp://127.0.0.1:5556}
stop_timeout=${EVOSLAM_STOP_TIMEOUT:-30}
if [[ ! $stop_timeout =~ ^[0-9]+$ ]]; then
  echo "local-cluster: EVOSLAM_STOP_TIMEOUT must be whole seconds, not '$stop_timeout'" >&2
  exit 2
fi
coordinator_bin=$bin/coordinator/evoslam-coordinator
worker_bin=$bin/worker/evoslam-worker
cli_bin=$bin/cli/evoslam
# How to call this script again for the same cluster.
self=$0
[[ -n ${EVOSLAM_RUN_DIR:-} ]] && self="EVOSLAM_RUN_DIR=$EVOSLAM_RUN_DIR $0"

usage() {
  echo "usage: $0 start [N] [--insecure] | stop | status" >&2
  echo "  start [N]  a coordinator and N workers (default: $(nproc), the cores) in $run_dir" >&2
  echo "             --insecure: allow endpoints other hosts reach (CURVE is off)" >&2
  echo "  stop       SIGTERM to all of them, waiting up to EVOSLAM_STOP_TIMEOUT s" >&2
  echo "  status     which processes run, and the coordinator's workers and jobs" >&2
  exit 2
}

# A bound endpoint's address for connecting: a wildcard bind is reached on the loopback.
connect_endpoint() {
  local e=$1
  e=${e/\/\/\*:/\/\/127.0.0.1:}
  echo "${e/\/\/0.0.0.0:/\/\/127.0.0.1:}"
}
clients_connect=$(connect_endpoint "$clients")
workers_connect=$(connect_endpoint "$workers")
# status and stop go by the endpoint the cluster was started with, whatever the environment says.
if [[ $action != start && -f $run_dir/clients.endpoint ]]; then
  clients_connect=$(<"$run_dir/clients.endpoint")
fi

# The pid in a pid file if that process is alive and still ours (pids get reused), else nothing.
live_pid() {
  local file=$1 name=$2 pid
  [[ -f $file ]] || return 0
  pid=$(<"$file")
  [[ $pid =~ ^[0-9]+$ ]] || return 0
  if [[ -r /proc/$pid/cmdline ]] && tr '\0' ' ' < "/proc/$pid/cmdline" | grep -q -- "$name"; then
    echo "$pid"
  fi
}

# Every "NAME PIDFILE" pair of this run dir, workers first so that they are stopped first.
pid_files() {
  local f
  for f in "$run_dir"/worker-*.pid; do
    [[ -e $f ]] && echo "evoslam-worker $f"
  done
  [[ -e $run_dir/coordinator.pid ]] && echo "evoslam-coordinator $run_dir/coordinator.pid"
  return 0
}

indent() { sed 's/^/  /'; }

# Whether a process still runs: an exited one may linger as a zombie until init reaps it.
alive() {
  local stat
  stat=$(cat "/proc/$1/stat" 2> /dev/null) || return 1
  stat=${stat##*) }
  [[ ${stat%% *} != Z ]]
}

cli() { "$cli_bin" "$1" --coordinator "$clients_connect" "${@:2}"; }

stop_all() {
  local name file pid pids=() names=() waited=0 left=() i
  while read -r name file; do
    pid=$(live_pid "$file" "$name")
    if [[ -n $pid ]]; then
      pids+=("$pid")
      names+=("$(basename "$file" .pid)")
    fi
    rm -f "$file"
  done < <(pid_files)
  if ((${#pids[@]} == 0)); then
    echo "local-cluster: nothing running in $run_dir"
    return 0
  fi
  # Workers first: each finishes its task within --grace or hands it back to the coordinator.
  for i in "${!pids[@]}"; do
    if [[ ${names[i]} == worker-* ]]; then kill -TERM "${pids[i]}" 2> /dev/null || true; fi
  done
  while :; do
    left=()
    for i in "${!pids[@]}"; do
      if [[ ${names[i]} == worker-* ]] && alive "${pids[i]}"; then left+=("$i"); fi
    done
    ((${#left[@]} == 0 || waited >= stop_timeout * 10)) && break
    sleep 0.1
    waited=$((waited + 1))
  done
  for i in "${!pids[@]}"; do
    if [[ ${names[i]} == coordinator ]]; then kill -TERM "${pids[i]}" 2> /dev/null || true; fi
  done
  while :; do
    left=()
    for i in "${!pids[@]}"; do
      if alive "${pids[i]}"; then left+=("$i"); fi
    done
    ((${#left[@]} == 0 || waited >= stop_timeout * 10)) && break
    sleep 0.1
    waited=$((waited + 1))
  done
  if ((${#left[@]} > 0)); then
    for i in "${left[@]}"; do
      echo "local-cluster: ${names[i]} (pid ${pids[i]}) still runs after ${stop_timeout} s;" \
        "killing it" >&2
      kill -KILL "${pids[i]}" 2> /dev/null || true
    done
    return 1
  fi
  echo "local-cluster: stopped ${#pids[@]} processes (${names[*]}) in $((waited / 10)) s"
}

start() {
  local n=$1 i pid waited=0 running=()
  for b in "$coordinator_bin" "$worker_bin" "$cli_bin"; do
    if [[ ! -x $b ]]; then
      echo "local-cluster: $b is missing; build first (deploy/build.sh) or set EVOSLAM_BIN" >&2
      exit 1
    fi
  done
  while read -r name file; do
    pid=$(live_pid "$file" "$name")
    [[ -n $pid ]] && running+=("$(basename "$file" .pid) (pid $pid)")
  done < <(pid_files)
  if ((${#running[@]} > 0)); then
    echo "local-cluster: already running from $run_dir: ${running[*]};" \
      "run '$self stop' first" >&2
    exit 1
  fi
  # This cluster runs without CURVE: an endpoint other hosts reach needs --insecure, as the
  # coordinator itself does.
  local endpoint insecure_flag=()
  for endpoint in "$clients" "$workers"; do
    case $endpoint in tcp://127.* | tcp://localhost:* | "tcp://[::1]:"* | ipc://* | inproc://*) ;;
      *)
        if [[ $insecure != 1 ]]; then
          echo "local-cluster: refusing $endpoint: other hosts reach it and CURVE is off;" \
            "give start --insecure to run so on a network you trust (docs/service.md)" >&2
          exit 2
        fi
        echo "local-cluster: warning: $endpoint is reachable from other hosts and CURVE is off" >&2
        insecure_flag=(--insecure)
        ;;
    esac
  done
  mkdir -p "$run_dir"
  rm -f "$run_dir"/*.pid
  echo "$clients_connect" > "$run_dir/clients.endpoint"
  # Several OpenMP processes share the cores: spinning threads would starve the others.
  export OMP_WAIT_POLICY=passive
  # setsid: the processes outlive this shell and a Ctrl-C in its terminal.
  setsid "$coordinator_bin" --clients "$clients" --workers "$workers" --db "$run_dir/jobs.db" \
    "${insecure_flag[@]}" < /dev/null >> "$run_dir/coordinator.log" 2>&1 &
  echo $! > "$run_dir/coordinator.pid"
  for ((i = 1; i <= n; i++)); do
    mkdir -p "$run_dir/cache/worker-$i"
    setsid "$worker_bin" --connect "$workers_connect" --threads 1 \
      --cache-dir "$run_dir/cache/worker-$i" < /dev/null >> "$run_dir/worker-$i.log" 2>&1 &
    echo $! > "$run_dir/worker-$i.pid"
  done
  # Ready when the coordinator answers a client and every worker has said Ready.
  local connected=0
  while :; do
    if [[ -z $(live_pid "$run_dir/coordinator.pid" evoslam-coordinator) ]]; then
      echo "local-cluster: the coordinator exited; the end of $run_dir/coordinator.log:" >&2
      tail -n 5 "$run_dir/coordinator.log" >&2
      stop_all > /dev/null || true
      exit 1
    fi
    if listing=$(cli workers --timeout 1 2> /dev/null); then
      connected=$(grep -cE 'tasks? done$' <<< "$listing" || true)
      ((connected >= n)) && break
    fi
    if ((waited >= 300)); then
      echo "local-cluster: after 30 s, $connected of $n workers are connected; see the logs in" \
        "$run_dir" >&2
      break
    fi
    sleep 0.1
    waited=$((waited + 1))
  done
  echo "local-cluster: coordinator (clients $clients, workers $workers) and $connected of $n" \
    "workers running; logs, pids and jobs.db in $run_dir"
  cat << EOF
Submit a job:
  $cli_bin simulate --world s-corridor --noise-uniform 0.2 --seed 1 --out out/sim
  $cli_bin localize --map out/sim/world.lines --log out/sim/log.clf --max-scans 40 \\
    --optimizer island --islands 2 --out out/cluster --coordinator $clients_connect
Follow it: $cli_bin jobs --coordinator $clients_connect (also status, watch, result, cancel)
Status: $self status
Stop: $self stop
EOF
}

status() {
  local name file pid any=0 coordinator=""
  while read -r name file; do
    pid=$(live_pid "$file" "$name")
    any=1
    if [[ -n $pid ]]; then
      echo "$(basename "$file" .pid): running (pid $pid)"
    else
      echo "$(basename "$file" .pid): not running (stale $file)"
    fi
    [[ $name == evoslam-coordinator ]] && coordinator=$pid
  done < <(pid_files)
  if ((any == 0)); then
    echo "local-cluster: not running (no pid files in $run_dir)"
    return 3
  fi
  if [[ -z $coordinator ]]; then
    return 3
  fi
  # Each list, or the error the command gave; only silence makes the status a failure.
  local what listing result=0
  for what in workers jobs; do
    echo "$what:"
    if listing=$(cli "$what" --timeout 3 2>&1); then
      [[ -n $listing ]] || listing=none
    elif [[ $listing == *"no answer from the coordinator"* ]]; then
      result=1
    fi
    indent <<< "$listing"
  done
  return "$result"
}

case $action in
  start)
    insecure=0
    if [[ ${!#} == --insecure ]]; then
      insecure=1
      set -- "${@:1:$#-1}"
    fi
    (($# <= 2)) || usage
    n=${2:-$(nproc)}
    [[ $n =~ ^[1-9][0-9]{0,2}$ ]] || usage
    start "$n"
    ;;
  stop)
    (($# == 1)) || usage
    stop_all
    ;;
  status)
    (($# == 1)) || usage
    status
    ;;
  *) usage ;;
esac
