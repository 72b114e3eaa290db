# A single-node Slurm cluster in a folder (sourced by tests/e2e/slurm/run.sh; the recipe of
# /work/shared/PLATFORM.md): munged, slurmctld and slurmd of Debian's packages, config and state in
# $CLUSTER, listening on 127.0.0.1 on two free ports. cluster_start exports SLURM_CONF for the
# client commands; cluster_stop stops the daemons by their pid files (call it from a trap).

free_ports() { # two free TCP ports on 127.0.0.1
  python3 - <<'PY'
import socket
socks = []
for _ in range(2):
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    socks.append(s)
print(" ".join(str(s.getsockname()[1]) for s in socks))
PY
}

cluster_start() {
  local d=$CLUSTER ports ctld_port d_port
  mkdir -p "$d"/{state,spool,log,munge}
  chmod 700 "$d/munge"
  dd if=/dev/urandom of="$d/munge/munge.key" bs=1024 count=1 status=none
  chmod 600 "$d/munge/munge.key"
  munged --key-file="$d/munge/munge.key" --socket="$d/munge/sock" --pid-file="$d/munge/pid" \
    --log-file="$d/munge/log" --seed-file="$d/munge/seed" -f
  read -r ctld_port d_port <<<"$(free_ports)"
  cat >"$d/slurm.conf" <<CONF
ClusterName=vt
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
AuthType=auth/munge
AuthInfo=socket=$d/munge/sock
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/ctld.pid
SlurmdPidFile=$d/d.pid
SlurmctldLogFile=$d/log/ctld.log
SlurmdLogFile=$d/log/d.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobAcctGatherType=jobacct_gather/none
MpiDefault=none
ReturnToService=2
SchedulerParameters=sched_interval=1
MinJobAge=600
NodeName=localhost NodeAddr=127.0.0.1 CPUs=2 RealMemory=4000 State=UNKNOWN
PartitionName=main Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF=$d/slurm.conf
  slurmctld -f "$SLURM_CONF"
  slurmd -f "$SLURM_CONF" -N localhost # the node of slurm.conf, whatever the hostname
  local i
  for i in $(seq 1 60); do
    if sinfo -h -o %T 2>/dev/null | grep -qx idle; then
      return 0
    fi
    sleep 0.5
  done
  echo "the cluster did not come up: node state '$(sinfo -h -o %T 2>&1)'" >&2
  tail -5 "$d/log/ctld.log" "$d/log/d.log" >&2 || true
  return 1
}

cluster_stop() {
  local d=$CLUSTER f pid pids=()
  for f in "$d/d.pid" "$d/ctld.pid" "$d/munge/pid"; do
    [ -f "$f" ] && pid=$(cat "$f") && kill "$pid" 2>/dev/null && pids+=("$pid")
  done
  local i
  for i in $(seq 1 40); do
    local alive=0
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    [ $alive = 0 ] && return 0
    sleep 0.25
  done
  for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
}
