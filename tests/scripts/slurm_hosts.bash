# A real three-node Slurm for one test, each node a "host" of its own: every
# slurmd runs in its own network namespace (veth to a bridge, its own
# address) and UTS namespace (its own hostname), slurmctld in a fourth; the
# filesystem is shared, as a cluster's is, and munge's socket with it.
# Sourced after cluster_lib.bash, not run. Every process of a host runs
# through in_host: nsenter into its network namespace, then a UTS and mount
# namespace of its own with its hostname and the cluster's hosts file bound
# over /etc/hosts (nothing else of the machine changes; /sys and cgroups stay
# the machine's, which slurmd needs). Teardown (also on failure): scancel,
# stop the daemons, then end whatever is left in the namespaces (by `ip netns
# pids`, nothing else) and delete them.
#
#   start_slurm_hosts        # three nodes wbh<id>1..3; exports SLURM_CONF
#   on_ctl CMD...            # run CMD on the controller's host (sbatch, squeue, clients)
#   kill_host K              # SIGKILL everything on host K (its slurmd, steps, workers)
#   slurm_job_state JOB, wait_slurm_job_end TIMEOUT_S JOB
command -v ip >/dev/null || fail "ip not found (iproute2)"
command -v unshare >/dev/null && command -v nsenter >/dev/null || fail "unshare/nsenter not found (util-linux)"

SLURM_DIR=$TMP/slurm
HID=$$
NET=10.$((200 + HID % 50)).$((HID / 50 % 250)).
CTL_NS=wb${HID}ctl
SW_NS=wb${HID}sw
host_name() { echo "wbh${HID}$1"; }
host_ns() { echo "wb${HID}h$1"; }
host_addr() { echo "${NET}$((10 + $1))"; }
CTL_ADDR=${NET}1
HOST_NS=()
SLURM_PIDS=()

# in_host NS HOSTNAME CMD...: CMD on that host; every step execs, so $! of a
# backgrounded in_host is CMD's pid.
in_host() {
  nsenter --net="/run/netns/$1" unshare --uts --mount sh -c \
    'mount --bind "$0" /etc/hosts && hostname "$1" && shift && exec "$@"' \
    "$SLURM_DIR/hosts" "$2" "${@:3}"
}
on_ctl() { in_host "$CTL_NS" "wbctl$HID" "$@"; }

ns_pids() { ip netns pids "$1" 2>/dev/null || true; }

kill_host() {
  local pid
  for pid in $(ns_pids "$(host_ns "$1")"); do kill -KILL "$pid" 2>/dev/null || true; done
}

stop_slurm_hosts() {
  [[ -f $SLURM_DIR/slurm.conf ]] || return 0
  local deadline pid ns
  on_ctl scancel --full --quiet --user=root 2>/dev/null || true
  deadline=$((SECONDS + 15))
  while [[ -n $(on_ctl squeue -h -o %i 2>/dev/null) ]] && ((SECONDS < deadline)); do sleep 0.3; done
  for pid in "${SLURM_PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  deadline=$((SECONDS + 10))
  for pid in "${SLURM_PIDS[@]}"; do
    while kill -0 "$pid" 2>/dev/null && ((SECONDS < deadline)); do sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
  done
  for ns in "${HOST_NS[@]}" "$CTL_NS" "$SW_NS"; do
    for pid in $(ns_pids "$ns"); do kill -KILL "$pid" 2>/dev/null || true; done
    ip netns del "$ns" 2>/dev/null || true
  done
}
trap 'stop_slurm_hosts; cleanup' EXIT

# A namespace on the bridge: veth "wb<id>p<tag>" in the switch, eth0 inside.
attach() {
  local ns=$1 tag=$2 addr=$3
  ip netns add "$ns"
  ip -n "$ns" link set lo up
  ip link add "wb${HID}p$tag" netns "$SW_NS" type veth peer name eth0 netns "$ns"
  ip -n "$SW_NS" link set "wb${HID}p$tag" master br0 up
  ip -n "$ns" addr add "$addr/24" dev eth0
  ip -n "$ns" link set eth0 up
}

start_slurm_hosts() {
  local bin k ns
  for bin in munged slurmctld slurmd sbatch srun squeue scancel scontrol; do
    command -v "$bin" >/dev/null ||
      fail "$bin not found: scripts/setup.sh installs munge, slurmctld, slurmd and slurm-client"
  done
  ip netns add "$SW_NS" || fail "cannot create network namespaces (needs root / CAP_NET_ADMIN)"
  ip -n "$SW_NS" link add br0 type bridge
  ip -n "$SW_NS" link set br0 up
  attach "$CTL_NS" c "$CTL_ADDR"
  for k in 1 2 3; do
    HOST_NS+=("$(host_ns "$k")")
    attach "$(host_ns "$k")" "$k" "$(host_addr "$k")"
  done
  mkdir -p "$SLURM_DIR"/{munge,state,spool,log}
  {
    echo "127.0.0.1 localhost"
    echo "$CTL_ADDR wbctl$HID"
    for k in 1 2 3; do echo "$(host_addr "$k") $(host_name "$k")"; done
  } >"$SLURM_DIR/hosts"
  for k in 1 2 3; do mkdir -p "$SLURM_DIR/spool/$(host_name "$k")"; done
  chmod 711 "$SLURM_DIR/munge"
  head -c 1024 /dev/urandom >"$SLURM_DIR/munge/munge.key"
  chmod 400 "$SLURM_DIR/munge/munge.key"
  munged -F -f --socket="$SLURM_DIR/munge/sock" --key-file="$SLURM_DIR/munge/munge.key" \
    --log-file="$SLURM_DIR/log/munged.log" --pid-file="$SLURM_DIR/munge/pid" \
    --seed-file="$SLURM_DIR/munge/seed" >"$TMP/munged.log" 2>&1 &
  SLURM_PIDS+=($!)
  wait_until 10 "munged's socket" test -S "$SLURM_DIR/munge/sock"
  {
    cat <<CONF
ClusterName=wbhosts$HID
SlurmctldHost=wbctl$HID($CTL_ADDR)
SlurmctldPort=6817
SlurmdPort=6818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$SLURM_DIR/munge/sock
StateSaveLocation=$SLURM_DIR/state
SlurmdSpoolDir=$SLURM_DIR/spool/%n
SlurmctldPidFile=$SLURM_DIR/slurmctld.pid
SlurmdPidFile=$SLURM_DIR/slurmd-%n.pid
SlurmctldLogFile=$SLURM_DIR/log/slurmctld.log
SlurmdLogFile=$SLURM_DIR/log/slurmd-%n.log
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
SlurmdParameters=config_overrides
SlurmdTimeout=6
SlurmctldTimeout=10
MessageTimeout=5
KillWait=5
InactiveLimit=0
MinJobAge=600
SchedulerParameters=sched_interval=1
CONF
    for k in 1 2 3; do
      echo "NodeName=$(host_name "$k") NodeAddr=$(host_addr "$k") NodeHostname=$(host_name "$k") CPUs=2 State=UNKNOWN"
    done
    echo "PartitionName=wb Nodes=$(host_name 1),$(host_name 2),$(host_name 3) Default=YES MaxTime=UNLIMITED State=UP"
  } >"$SLURM_DIR/slurm.conf"
  export SLURM_CONF=$SLURM_DIR/slurm.conf
  in_host "$CTL_NS" "wbctl$HID" slurmctld -D -i -f "$SLURM_CONF" >"$TMP/slurmctld.log" 2>&1 &
  SLURM_PIDS+=($!)
  for k in 1 2 3; do start_slurmd "$k"; done
  wait_until 40 "three idle Slurm nodes" slurm_hosts_idle
}

start_slurmd() {
  local k=$1
  in_host "$(host_ns "$k")" "$(host_name "$k")" slurmd -D -N "$(host_name "$k")" -f "$SLURM_CONF" \
    >"$TMP/slurmd$k.log" 2>&1 &
  SLURM_PIDS+=($!)
}

slurm_hosts_idle() { (($(on_ctl sinfo -h -N -o %T | grep -cx idle) == 3)); }

slurm_job_state() { on_ctl scontrol show job "$1" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p'; }

slurm_job_ended() { [[ $(slurm_job_state "$1") =~ ^(COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|PREEMPTED)$ ]]; }

wait_slurm_job_end() { wait_until "$1" "Slurm job $2 to end" slurm_job_ended "$2"; }
