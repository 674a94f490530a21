#!/usr/bin/env bash
# The service across hosts, on one machine: network namespaces stand in for a coordinator host,
# two worker hosts and a client host, joined by veth pairs to a bridge in a fifth "switch"
# namespace (so the host's own network is never touched). CURVE is on, with keys from
# `evoslam keygen`. It checks that a small island job succeeds with both workers doing tasks,
# that a second accepted client key sees none of the first key's jobs, that a client or a worker
# whose key is not accepted gets no service, and that a coordinator without CURVE refuses the
# host's network address. Everything it made
# is removed on exit, pass or fail. Needs root and iproute2.
# Usage: deploy/netns-test.sh   (binaries from EVOSLAM_BIN, default build/)
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
bin=$(realpath -m "${EVOSLAM_BIN:-$root/build}")
evoslam=$bin/cli/evoslam
net=10.231.0       # a /24 that only exists inside the namespaces
tag=evs$$          # namespace and link names unique to this run
sw=$tag-sw
coord=$tag-coord
client=$tag-cli
nodes=("$coord" "$tag-w1" "$tag-w2" "$client")
coordinator_ip=$net.1
clients_ep=tcp://$coordinator_ip:5555
workers_ep=tcp://$coordinator_ip:5556

if [[ $(id -u) -ne 0 ]]; then
  echo "netns-test: needs root (network namespaces)" >&2
  exit 1
fi
command -v ip > /dev/null || {
  echo "netns-test: needs ip (iproute2; deploy/install-deps.sh installs it)" >&2
  exit 1
}
for b in "$evoslam" "$bin/coordinator/evoslam-coordinator" "$bin/worker/evoslam-worker"; do
  [[ -x $b ]] || {
    echo "netns-test: $b is missing; build first or set EVOSLAM_BIN" >&2
    exit 1
  }
done

tmp=$(mktemp -d /tmp/evoslam-netns.XXXXXX)
pids=()
result=FAIL

# The trap may fire inside a command whose output is redirected; it reports on these.
exec 3>&1 4>&2
cleanup() {
  local status=$? pid
  set +e
  exec 1>&3 2>&4
  # SIGTERM first so the processes close their sockets; a namespace goes only with its last
  # process, so whatever still runs in one (a client cut short) is stopped too.
  in_namespaces() { for ns in "${nodes[@]}"; do ip netns pids "$ns" 2> /dev/null; done; }
  for pid in "${pids[@]}" $(in_namespaces); do kill -TERM "$pid" 2> /dev/null; done
  for _ in $(seq 100); do
    [[ -z $(in_namespaces) ]] && break
    sleep 0.1
  done
  for pid in $(in_namespaces); do kill -KILL "$pid" 2> /dev/null; done
  wait 2> /dev/null
  if [[ $result != PASS ]]; then
    for log in "$tmp"/*.log; do
      [[ -e $log ]] || continue
      echo "--- last lines of $(basename "$log")" >&2
      tail -n 15 "$log" >&2
    done
  fi
  for ns in "${nodes[@]}" "$sw"; do ip netns del "$ns" 2> /dev/null; done
  rm -rf "$tmp"
  echo "netns-test: $result"
  [[ $result == PASS ]] || exit $((status ? status : 1))
}
trap cleanup EXIT
trap 'exit 130' INT TERM

fail() {
  echo "netns-test: $*" >&2
  exit 1
}

# Whether a process still runs: an exited child stays a zombie until it is waited for.
alive() {
  local stat
  stat=$(cat "/proc/$1/stat" 2> /dev/null) || return 1
  stat=${stat##*) }
  [[ ${stat%% *} != Z ]]
}

in_ns() {
  local ns=$1
  shift
  ip netns exec "$ns" "$@"
}

# --- network: each node has eth0 = 10.231.0.N, its peer enslaved to br0 in the switch ---
ip netns add "$sw"
ip -n "$sw" link add br0 type bridge
ip -n "$sw" link set br0 up
for i in "${!nodes[@]}"; do
  ns=${nodes[i]}
  ip netns add "$ns"
  ip -n "$ns" link set lo up
  ip link add "$tag-$i" netns "$ns" type veth peer name "port$i" netns "$sw"
  ip -n "$ns" link set "$tag-$i" name eth0
  ip -n "$ns" addr add "$net.$((i + 1))/24" dev eth0
  ip -n "$ns" link set eth0 up
  ip -n "$sw" link set "port$i" master br0 up
done

# --- keys: a pair for each party; the coordinator accepts the folders' public keys only ---
mkdir -p "$tmp/keys" "$tmp/accepted-clients" "$tmp/accepted-workers"
for name in coordinator worker1 worker2 client client2 intruder; do
  "$evoslam" keygen --name "$name" --out "$tmp/keys" > /dev/null
done
cp "$tmp/keys/client.pub" "$tmp/keys/client2.pub" "$tmp/accepted-clients/"
cp "$tmp/keys/worker1.pub" "$tmp/keys/worker2.pub" "$tmp/accepted-workers/"

# --- service: coordinator bound to its 10.x address, one single-threaded worker per host ---
export OMP_WAIT_POLICY=passive
# `ip netns exec` execs the program, so $! is its pid (through a shell function it would not be).
ip netns exec "$coord" "$bin/coordinator/evoslam-coordinator" --clients "$clients_ep" \
  --workers "$workers_ep" --db "$tmp/jobs.db" --curve-secret-key "$tmp/keys/coordinator.key" \
  --client-keys "$tmp/accepted-clients" --worker-keys "$tmp/accepted-workers" \
  > "$tmp/coordinator.log" 2>&1 &
pids+=($!)
for w in 1 2; do
  ip netns exec "$tag-w$w" "$bin/worker/evoslam-worker" --connect "$workers_ep" --threads 1 \
    --curve-server-key "$tmp/keys/coordinator.pub" --curve-key "$tmp/keys/worker$w.key" \
    > "$tmp/worker$w.log" 2>&1 &
  pids+=($!)
done
# A worker whose key is not accepted, on the client's host: it must never be listed.
ip netns exec "$client" "$bin/worker/evoslam-worker" --connect "$workers_ep" --threads 1 \
  --curve-server-key "$tmp/keys/coordinator.pub" --curve-key "$tmp/keys/intruder.key" \
  > "$tmp/intruder-worker.log" 2>&1 &
intruder_worker=$!

as_client() {
  in_ns "$client" "$evoslam" "$@" --coordinator "$clients_ep" \
    --curve-server-key "$tmp/keys/coordinator.pub" --curve-key "$tmp/keys/client.key"
}
# Another accepted client, on the same host: it must see none of the first one's jobs.
as_client2() {
  in_ns "$client" "$evoslam" "$@" --coordinator "$clients_ep" \
    --curve-server-key "$tmp/keys/coordinator.pub" --curve-key "$tmp/keys/client2.key"
}

listing=""
for _ in $(seq 60); do
  for pid in "${pids[@]}"; do alive "$pid" || fail "a service process exited"; done
  listing=$(as_client workers --timeout 2 2> /dev/null) || true
  (($(grep -cE 'tasks? done$' <<< "$listing") == 2)) && break
  sleep 0.5
done
(($(grep -cE 'tasks? done$' <<< "$listing") == 2)) ||
  fail "not exactly two workers within 30 s; the coordinator lists: ${listing:-nothing}"
echo "netns-test: coordinator at $coordinator_ip with CURVE, 2 workers connected"

# --- a small island job from the client host ---
"$evoslam" simulate --world s-corridor --noise-uniform 0.2 --seed 1 --out "$tmp/sim" > /dev/null
in_ns "$client" timeout 300 "$evoslam" localize --map "$tmp/sim/world.lines" \
  --log "$tmp/sim/log.clf" --max-scans 40 --optimizer island --islands 2 --out "$tmp/out" \
  --coordinator "$clients_ep" --curve-server-key "$tmp/keys/coordinator.pub" \
  --curve-key "$tmp/keys/client.key" > "$tmp/localize.log" 2>&1 ||
  fail "the job did not succeed: $(tail -n 3 "$tmp/localize.log")"
scans=$(grep -vc '^#' "$tmp/out/trajectory.txt")
((scans == 40)) || fail "the job's trajectory has $scans poses, not 40"
jobs=$(as_client jobs --timeout 5)
job_id=$(grep -oE '^job-[0-9a-f]{32}' <<< "$jobs" | head -n 1)
[[ -n $job_id ]] && grep -q "^$job_id  succeeded" <<< "$jobs" ||
  fail "evoslam jobs does not show the job succeeded, under a random id: $jobs"
echo "netns-test: island job succeeded ($scans poses): $(grep 'RMS error' "$tmp/localize.log" | xargs)"

# --- ownership: the second client key sees nothing of the first one's job ---
jobs2=$(as_client2 jobs --timeout 5) || fail "the second client could not list jobs: $jobs2"
[[ $jobs2 != *job-* ]] || fail "the second client lists the first one's jobs: $jobs2"
for command in status cancel; do
  if out=$(as_client2 "$command" "$job_id" --timeout 5 2>&1); then
    fail "the second client could $command the first one's job: $out"
  fi
  [[ $out == *"no job $job_id"* ]] || fail "$command by the second client failed otherwise: $out"
done
if out=$(as_client2 result "$job_id" --out "$tmp/stolen" --timeout 5 2>&1) || [[ -e $tmp/stolen ]]; then
  fail "the second client fetched the first one's result: $out"
fi
grep -q "^$job_id  succeeded" <<< "$(as_client jobs --timeout 5)" ||
  fail "the job is no longer the first client's, or no longer succeeded"
echo "netns-test: a second client key sees none of the first one's jobs (jobs, status, cancel, result)"

# --- without CURVE the coordinator refuses the host's network address ---
set +e
ip netns exec "$coord" "$bin/coordinator/evoslam-coordinator" --clients "tcp://$coordinator_ip:5557" \
  --workers "tcp://127.0.0.1:5558" --db "$tmp/plain.db" > "$tmp/plain.log" 2>&1
status=$?
set -e
((status == 2)) && grep -q "without CURVE" "$tmp/plain.log" ||
  fail "a coordinator without CURVE on $coordinator_ip exited $status: $(cat "$tmp/plain.log")"
echo "netns-test: without CURVE the coordinator refused tcp://$coordinator_ip:5557 (exit 2)"

# --- both workers did some of it ---
listing=$(as_client workers --timeout 5)
awk '{ print "  " $0 }' <<< "$listing"
busy_workers=$(awk '/tasks? done$/ && $(NF - 2) > 0' <<< "$listing" | wc -l)
((busy_workers == 2)) || fail "$busy_workers workers, not 2, did tasks"

# --- no service without an accepted key: neither an unknown key nor plain ZeroMQ ---
refused() {
  local what=$1 t0 elapsed
  shift
  t0=$(date +%s%N)
  if in_ns "$client" "$evoslam" workers --coordinator "$clients_ep" --timeout 3 "$@" \
    > "$tmp/refused.out" 2>&1; then
    fail "a client with $what was served: $(cat "$tmp/refused.out")"
  fi
  elapsed=$((($(date +%s%N) - t0) / 1000000))
  grep -qF "no answer from the coordinator at $clients_ep within 3 s" "$tmp/refused.out" ||
    fail "a client with $what failed otherwise than by the timeout: $(cat "$tmp/refused.out")"
  ((elapsed < 6000)) || fail "a client with $what took $elapsed ms to give up, not about 3 s"
  echo "netns-test: a client with $what got no answer (gave up after $elapsed ms)"
}
refused "a key the coordinator does not accept" \
  --curve-server-key "$tmp/keys/coordinator.pub" --curve-key "$tmp/keys/intruder.key"
refused "no CURVE key"
for domain in clients workers; do
  grep -qF "($domain): public key $(<"$tmp/keys/intruder.pub") is not accepted" \
    "$tmp/coordinator.log" || fail "the coordinator's log does not name the key it refused to $domain"
done
echo "netns-test: a worker with that key was refused too (never listed, refusal logged)"
# SIGKILL: a worker refused at the handshake blocks for good in a send and ignores SIGTERM.
kill -KILL "$intruder_worker"
wait "$intruder_worker" 2> /dev/null || true

result=PASS
