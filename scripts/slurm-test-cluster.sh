#!/usr/bin/env bash
# A private Slurm for the `slurm` tests: munged, slurmctld and slurmd with a generated configuration,
# everything (state, spool, logs, pid files, munge socket and key) in one directory. One node by
# default (slurmd -N localhost, all on loopback); with NODES > 1, a cluster on this machine: the
# controller (munged, slurmctld) on a bridge in this network namespace, and NODES compute nodes
# node1..nodeN, each slurmd in its own network namespace (`ip netns`) joined to the bridge by a veth
# pair, with its own address. All share the filesystem (as a cluster's shared filesystem) and the one
# munge key. It installs nothing: scripts/setup.sh installs slurmctld, slurmd, slurm-client, munge.
#
# Usage:
#   scripts/slurm-test-cluster.sh start DIR [NODES]  # generate DIR/slurm.conf, start the daemons, wait for idle
#   scripts/slurm-test-cluster.sh stop DIR           # stop the daemons (and remove the namespaces) of DIR (safe to repeat)
#   scripts/slurm-test-cluster.sh status DIR         # which daemons of DIR are alive (exit 1 if any is not)
#   scripts/slurm-test-cluster.sh kill-node DIR NODE # NODE dies: SIGKILL to every process in its namespace
#   scripts/slurm-test-cluster.sh start-node DIR NODE # start NODE's slurmd again, wait until it is idle
# Clients then need: export SLURM_CONF=DIR/slurm.conf. With NODES > 1, DIR/cluster.env holds the
# controller's address (SLURM_TEST_CONTROLLER) and the nodes' names, addresses and namespaces.
#
# Needs root (slurmd runs jobs as their submitting user; SlurmUser=root). Two clusters started
# in different directories must use different ports: set SLURM_TEST_PORT (default 16817; slurmd
# uses the next port). Each node of a multi-node cluster declares SLURM_TEST_NODE_CPUS CPUs
# (default 2, whatever the machine has) and the partition puts a job on the least loaded node.
set -euo pipefail

usage() { sed -n '2,26p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
[ $# -ge 2 ] && [ $# -le 3 ] || usage
action="$1"
dir="$(mkdir -p "$2" && cd "$2" && pwd)"
arg="${3:-}"
port="${SLURM_TEST_PORT:-16817}"
daemons=(slurmctld munged)

die() { echo "slurm-test-cluster: $*" >&2; exit 1; }

# The cluster's layout, written by start: NODES, the nodes' names, namespaces and addresses.
nodes=1
node_names=(localhost)
[ ! -s "$dir/cluster.env" ] || . "$dir/cluster.env"

# Alive means a process that is not a zombie: PID 1 on our machines does not reap, so a stopped
# daemon can stay in the process table, and `kill -0` would call it alive.
alive() {
  local pid="$1" state
  [ -r "/proc/$pid/stat" ] || return 1
  state="$(sed 's/^.*) //' "/proc/$pid/stat" | cut -d' ' -f1)"
  [ "$state" != Z ] && [ "$state" != X ]
}

pid_of() { [ -s "$dir/run/$1.pid" ] && cat "$dir/run/$1.pid" || true; }

# The processes whose parent is $1 (field 2 after the command name in /proc/PID/stat). Shell
# builtins only: a machine may have thousands of processes.
children_of() {
  local stat line fields
  for stat in /proc/[0-9]*/stat; do
    read -r line 2>/dev/null <"$stat" || continue
    read -r -a fields <<<"${line##*) }"
    [ "${fields[1]}" = "$1" ] || continue
    stat="${stat#/proc/}"
    echo "${stat%/stat}"
  done
}

kill_tree() {
  local child
  for child in $(children_of "$1"); do kill_tree "$child"; done
  kill -KILL "$1" 2>/dev/null || true
}

# Job steps outlive slurmd. A step left running (a test run killed half-way) reports its job's end
# to the next cluster started in this directory, which listens on the same port and numbers its jobs
# from 1 again: that cluster's job of the same number then ends at once, "completed" (seen once:
# a test's `sleep 600` job reported done after 3 s). So the steps of this cluster (their working
# directory is in $dir) go too, with the jobs they run.
kill_steps() {
  local proc comm
  for proc in /proc/[0-9]*; do
    read -r comm 2>/dev/null <"$proc/comm" || continue
    [ "$comm" = slurmstepd ] || continue
    case "$(readlink "$proc/cwd" 2>/dev/null)" in
    "$dir" | "$dir"/*) kill_tree "${proc#/proc/}" ;;
    esac
  done
}

# Every process in node $1's network namespace (its slurmd, its steps and their jobs) gets SIGKILL.
kill_namespace() {
  local ns="$1" pid
  ip netns list 2>/dev/null | grep -qw "^$ns" || return 0
  for pid in $(ip netns pids "$ns" 2>/dev/null); do kill -KILL "$pid" 2>/dev/null || true; done
}

stop_daemon() {
  local name="$1" pid i
  pid="$(pid_of "$name")"
  [ -n "$pid" ] || return 0
  if alive "$pid"; then
    kill -TERM "$pid" 2>/dev/null || true
    for i in $(seq 1 100); do alive "$pid" || break; sleep 0.1; done
    if alive "$pid"; then
      echo "slurm-test-cluster: $name (pid $pid) ignored SIGTERM for 10 s; sending SIGKILL" >&2
      kill -KILL "$pid" 2>/dev/null || true
    fi
  fi
  rm -f "$dir/run/$name.pid"
}

slurmd_name() { [ "$nodes" -eq 1 ] && echo slurmd || echo "slurmd-$1"; }

stop() {
  local node i
  for node in "${node_names[@]}"; do stop_daemon "$(slurmd_name "$node")"; done
  for name in "${daemons[@]}"; do stop_daemon "$name"; done
  kill_steps
  if [ "$nodes" -gt 1 ]; then
    for i in $(seq 1 "$nodes"); do
      kill_namespace "${node_ns[$i]}"
      ip netns del "${node_ns[$i]}" 2>/dev/null || true
    done
    ip link del "$bridge" 2>/dev/null || true
  fi
  rm -f "$dir/cluster.env"
}

status() {
  local name pid bad=0 node
  local names=("${daemons[@]}")
  for node in "${node_names[@]}"; do names+=("$(slurmd_name "$node")"); done
  for name in "${names[@]}"; do
    pid="$(pid_of "$name")"
    if [ -n "$pid" ] && alive "$pid"; then echo "$name: running (pid $pid)"; else echo "$name: not running"; bad=1; fi
  done
  return $bad
}

# A /24 that no interface of this namespace uses, and names no namespace or link has: from the port,
# so that two build trees' clusters do not collide.
pick_network() {
  local k i
  for i in $(seq 0 199); do
    k=$(((port + i) % 200 + 30))
    ip -o -4 addr show | grep -q " 10\.216\.$k\." && continue
    ip link show "gts${k}br" >/dev/null 2>&1 && continue
    ip netns list 2>/dev/null | grep -q "^gts${k}n" && continue
    echo "$k"
    return 0
  done
  return 1
}

# The bridge (the controller's address) and one namespace per node, written to cluster.env.
make_network() {
  local k i ns veth peer
  k="$(pick_network)" || die "no free 10.216.X.0/24 network for the test cluster"
  bridge="gts${k}br"
  {
    echo "nodes=$nodes"
    echo "bridge=$bridge"
    echo "SLURM_TEST_CONTROLLER=10.216.$k.1"
    echo "node_names=($(for i in $(seq 1 "$nodes"); do printf 'node%d ' "$i"; done))"
    echo "node_ns=('' $(for i in $(seq 1 "$nodes"); do printf 'gts%dn%d ' "$k" "$i"; done))"
    echo "node_addr=('' $(for i in $(seq 1 "$nodes"); do printf '10.216.%d.%d ' "$k" $((10 + i)); done))"
  } >"$dir/cluster.env"
  . "$dir/cluster.env"
  ip link add "$bridge" type bridge || die "cannot create a bridge (needs root and iproute2)"
  ip addr add "$SLURM_TEST_CONTROLLER/24" dev "$bridge"
  ip link set "$bridge" up
  for i in $(seq 1 "$nodes"); do
    ns="${node_ns[$i]}" veth="gts${k}v$i" peer="gts${k}p$i"
    ip netns add "$ns" || die "cannot create network namespace $ns (needs root and iproute2's 'ip netns')"
    ip link add "$veth" type veth peer name "$peer" netns "$ns"
    ip link set "$veth" master "$bridge"
    ip link set "$veth" up
    ip -n "$ns" addr add "${node_addr[$i]}/24" dev "$peer"
    ip -n "$ns" link set "$peer" up
    ip -n "$ns" link set lo up
  done
}

write_config() {
  local cpus mem_mb controller i
  cpus="$(nproc)"
  mem_mb="$(awk '/MemTotal/ {printf "%d", $2 / 1024 * 0.9}' /proc/meminfo)"
  controller=localhost
  if [ "$nodes" -gt 1 ]; then
    cpus="${SLURM_TEST_NODE_CPUS:-2}"
    mem_mb=$((mem_mb / nodes))
    # slurmctld checks that its host's name is the controller's; the address is the bridge's.
    controller="$(hostname -s)($SLURM_TEST_CONTROLLER)"
  fi
  cat >"$dir/slurm.conf" <<CONF
# Generated by scripts/slurm-test-cluster.sh for the geotandem tests; private to $dir.
ClusterName=geotandem-test
SlurmctldHost=$controller
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
EnforcePartLimits=ALL
MailProg=/bin/true
MpiDefault=none
ReturnToService=2
MinJobAge=300
SchedulerType=sched/backfill
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
AcctGatherEnergyType=acct_gather_energy/none
StateSaveLocation=$dir/state
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmctldLogFile=$dir/log/slurmctld.log
CONF
  if [ "$nodes" -eq 1 ]; then
    cat >>"$dir/slurm.conf" <<CONF
SlurmdTimeout=30
SlurmdSpoolDir=$dir/spool
SlurmdPidFile=$dir/run/slurmd.pid
SlurmdLogFile=$dir/log/slurmd.log
NodeName=localhost CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
    return
  fi
  # The nodes share this file; %n is each slurmd's node name. config_overrides: a node declares
  # the CPUs and memory given here, not what slurmd finds (all nodes are this one machine).
  # A dead node is declared down after SlurmdTimeout (10 s here, 300 s by default).
  cat >>"$dir/slurm.conf" <<CONF
SlurmdTimeout=10
SlurmdParameters=config_overrides
SlurmdSpoolDir=$dir/spool/%n
SlurmdPidFile=$dir/run/slurmd-%n.pid
SlurmdLogFile=$dir/log/slurmd-%n.log
CONF
  for i in $(seq 1 "$nodes"); do
    echo "NodeName=${node_names[$((i - 1))]} NodeAddr=${node_addr[$i]} CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN" >>"$dir/slurm.conf"
  done
  echo "PartitionName=debug Nodes=node[1-$nodes] Default=YES MaxTime=INFINITE State=UP LLN=YES" >>"$dir/slurm.conf"
}

node_index() {
  local i
  for i in $(seq 1 "$nodes"); do [ "${node_names[$((i - 1))]}" = "$1" ] && { echo "$i"; return 0; }; done
  die "no node '$1' in the cluster of $dir (nodes: ${node_names[*]})"
}

start_slurmd() {
  local node="$1" i
  if [ "$nodes" -eq 1 ]; then
    slurmd -f "$SLURM_CONF" -N "$node" || die "slurmd did not start; see $dir/log/slurmd.log"
  else
    i="$(node_index "$node")"
    mkdir -p "$dir/spool/$node"
    # nsenter, not `ip netns exec`: that remounts /sys without the cgroup filesystem slurmd needs.
    nsenter --net="/run/netns/${node_ns[$i]}" slurmd -f "$SLURM_CONF" -N "$node" ||
      die "slurmd of $node did not start; see $dir/log/slurmd-$node.log"
  fi
}

# Waits until every node named is idle (sinfo), at most $1 s.
wait_idle() {
  local until=$((SECONDS + $1)) begin=$SECONDS node state ok
  shift
  while [ $SECONDS -lt $until ]; do
    ok=1
    for node in "$@"; do
      state="$(sinfo -h -N -n "$node" -o %T 2>/dev/null | head -1)"
      [ "$state" = idle ] || { ok=0; break; }
    done
    if [ $ok -eq 1 ]; then
      echo "slurm-test-cluster: $* idle after $((SECONDS - begin)) s; export SLURM_CONF=$SLURM_CONF"
      return 0
    fi
    sleep 0.2
  done
  return 1
}

start() {
  local cmd node
  for cmd in munged mungekey slurmctld slurmd sinfo; do
    command -v "$cmd" >/dev/null || die "'$cmd' not found on PATH: run scripts/setup.sh (it installs slurmctld slurmd slurm-client munge)"
  done
  [ "$(id -u)" -eq 0 ] || die "needs root (slurmd with SlurmUser=root); run as root or skip the 'slurm' tests"
  local want="${arg:-1}"
  [[ "$want" =~ ^[1-9][0-9]?$ ]] || die "NODES must be a number from 1 to 99, not '$want'"
  if [ "$want" -eq "$nodes" ] && status >/dev/null 2>&1; then echo "slurm-test-cluster: already running in $dir"; return 0; fi
  stop
  nodes="$want"
  node_names=(localhost)
  mkdir -p "$dir"/{state,spool,run,log,munge}
  if [ "$nodes" -gt 1 ]; then
    command -v ip >/dev/null || die "'ip' (iproute2) not found: a multi-node test cluster needs network namespaces"
    make_network
  fi
  # munged refuses a socket whose directories others cannot enter (mktemp -d makes 0700).
  chmod 0755 "$dir" "$dir/munge"
  [ -s "$dir/munge/munge.key" ] || mungekey --create --keyfile="$dir/munge/munge.key"
  chmod 0400 "$dir/munge/munge.key"
  write_config

  # One munged for the cluster: its socket is a file, reachable from every network namespace.
  munged --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/run/munged.pid" --log-file="$dir/log/munged.log" --seed-file="$dir/munge/munge.seed" ||
    die "munged did not start; see $dir/log/munged.log"
  munge -S "$dir/munge/munge.socket" -n | unmunge -S "$dir/munge/munge.socket" >/dev/null ||
    die "munge self-test failed; see $dir/log/munged.log"

  export SLURM_CONF="$dir/slurm.conf"
  slurmctld -f "$SLURM_CONF" || die "slurmctld did not start; see $dir/log/slurmctld.log"
  for node in "${node_names[@]}"; do start_slurmd "$node"; done
  wait_idle 30 "${node_names[@]}" && return 0
  sinfo -N >&2 || true
  stop
  die "the nodes did not become idle within 30 s; see $dir/log/slurmctld.log and $dir/log/slurmd*.log"
}

kill_node() {
  [ "$nodes" -gt 1 ] || die "kill-node needs a multi-node cluster (start DIR NODES)"
  local i
  i="$(node_index "$arg")"
  kill_namespace "${node_ns[$i]}"
  rm -f "$dir/run/slurmd-$arg.pid"
  echo "slurm-test-cluster: $arg killed (every process in ${node_ns[$i]})"
}

start_node() {
  [ "$nodes" -gt 1 ] || die "start-node needs a multi-node cluster (start DIR NODES)"
  export SLURM_CONF="$dir/slurm.conf"
  local pid
  pid="$(pid_of "slurmd-$arg")"
  if [ -z "$pid" ] || ! alive "$pid"; then start_slurmd "$arg"; fi
  wait_idle 120 "$arg" || die "$arg did not become idle within 120 s: $(sinfo -h -N -n "$arg" -o '%T %E')"
}

case "$action" in
  start) start ;;
  stop) stop; echo "slurm-test-cluster: stopped ($dir)" ;;
  status) status ;;
  kill-node) [ -n "$arg" ] || usage; kill_node ;;
  start-node) [ -n "$arg" ] || usage; start_node ;;
  *) usage ;;
esac
