# A real single-node Slurm for one test (munged, slurmctld, slurmd as root,
# configured in $TMP/slurm with free ports, its own munge key and socket),
# sourced after cluster_lib.bash, not run. Teardown (also on failure):
# scancel every job of this cluster, wait for them to end, stop the daemons,
# then end any process still carrying this cluster's SLURM_CONF (a step's
# leftovers), found by that path, never by a name.
#
#   start_slurm           # exports SLURM_CONF; SLURM_NODE is the node's name
#   slurm_job_state JOB   # JobState of a job (COMPLETED, FAILED, RUNNING, ...)
#   wait_slurm_job_end TIMEOUT_S JOB

SLURM_DIR=$TMP/slurm
SLURM_NODE=wbnode$$

slurm_procs() {  # pids of processes of this cluster, by their environment
  grep -l -z -x -F "SLURM_CONF=$SLURM_DIR/slurm.conf" /proc/[0-9]*/environ 2>/dev/null |
    sed 's|^/proc/\([0-9]*\)/environ$|\1|' | grep -v -x -e "$$" -e "$BASHPID" || true
}

stop_slurm() {
  [[ -f $SLURM_DIR/slurm.conf ]] || return 0
  local deadline pid
  scancel --full --quiet --user=root 2>/dev/null || true
  deadline=$((SECONDS + 20))
  while [[ -n $(squeue -h -o %i 2>/dev/null) ]] && ((SECONDS < deadline)); do sleep 0.3; done
  for pid in "${SLURM_PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  deadline=$((SECONDS + 10))
  for pid in "${SLURM_PIDS[@]}"; do
    while kill -0 "$pid" 2>/dev/null && ((SECONDS < deadline)); do sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
  done
  for pid in $(slurm_procs); do kill -KILL "$pid" 2>/dev/null || true; done
}
SLURM_PIDS=()
trap 'stop_slurm; cleanup' EXIT

start_slurm() {
  local bin
  for bin in munged slurmctld slurmd sbatch srun squeue scancel scontrol; do
    command -v "$bin" >/dev/null ||
      fail "$bin not found: scripts/setup.sh installs munge, slurmctld, slurmd and slurm-client"
  done
  mkdir -p "$SLURM_DIR"/{munge,state,spool,log}
  chmod 711 "$SLURM_DIR/munge"
  head -c 1024 /dev/urandom >"$SLURM_DIR/munge/munge.key"
  chmod 400 "$SLURM_DIR/munge/munge.key"
  munged -F -f --socket="$SLURM_DIR/munge/sock" --key-file="$SLURM_DIR/munge/munge.key" \
    --log-file="$SLURM_DIR/log/munged.log" --pid-file="$SLURM_DIR/munge/pid" \
    --seed-file="$SLURM_DIR/munge/seed" >"$TMP/munged.log" 2>&1 &
  SLURM_PIDS+=($!)
  wait_until 10 "munged's socket" test -S "$SLURM_DIR/munge/sock"
  local ctl_port d_port
  ctl_port=$(free_port)
  d_port=$(free_port)
  cat >"$SLURM_DIR/slurm.conf" <<CONF
ClusterName=wbtest$$
SlurmctldHost=$(hostname)(127.0.0.1)
SlurmctldPort=$ctl_port
SlurmdPort=$d_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$SLURM_DIR/munge/sock
StateSaveLocation=$SLURM_DIR/state
SlurmdSpoolDir=$SLURM_DIR/spool
SlurmctldPidFile=$SLURM_DIR/slurmctld.pid
SlurmdPidFile=$SLURM_DIR/slurmd.pid
SlurmctldLogFile=$SLURM_DIR/log/slurmctld.log
SlurmdLogFile=$SLURM_DIR/log/slurmd.log
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
KillWait=5
InactiveLimit=0
MinJobAge=600
SchedulerParameters=sched_interval=1
NodeName=$SLURM_NODE NodeAddr=127.0.0.1 NodeHostname=$(hostname) CPUs=4 State=UNKNOWN
PartitionName=wb Nodes=$SLURM_NODE Default=YES MaxTime=UNLIMITED State=UP
CONF
  export SLURM_CONF=$SLURM_DIR/slurm.conf
  slurmctld -D -i -f "$SLURM_CONF" >"$TMP/slurmctld.log" 2>&1 &
  SLURM_PIDS+=($!)
  slurmd -D -N "$SLURM_NODE" -f "$SLURM_CONF" >"$TMP/slurmd.log" 2>&1 &
  SLURM_PIDS+=($!)
  wait_until 30 "the Slurm node to be idle" slurm_node_idle
}

slurm_node_idle() { sinfo -h -N -n "$SLURM_NODE" -o %T | grep -qx idle; }

slurm_job_state() { scontrol show job "$1" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p'; }

slurm_job_ended() { [[ $(slurm_job_state "$1") =~ ^(COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY)$ ]]; }

wait_slurm_job_end() { wait_until "$1" "Slurm job $2 to end" slurm_job_ended "$2"; }
