# Sourced by the shell checks: a ROS master of their own, on a port no one else has.
#   free_port            prints a TCP port free now, below the ephemeral ports (32768 up), so that
#                        no node's server or client socket takes it in the meantime
#   start_master LOG     roscore on a free port, up (answering) within 60 s: exports ROS_MASTER_URI,
#                        sets $port and $core (its pid); its output goes to LOG. A roscore that exits
#                        (its port taken meanwhile) is started again on another port, 3 tries.
#                        Fails with the reason in $master_failure.
free_port() {
  python3 - <<'EOF'
import random, socket
for _ in range(500):
    port = random.randrange(20000, 32768)
    with socket.socket() as s:
        try:
            s.bind(("", port))
        except OSError:
            continue
    print(port)
    break
EOF
}

start_master() {
  local log=$1 try deadline
  master_failure=""
  for try in 1 2 3; do
    port=$(free_port)
    export ROS_MASTER_URI=http://localhost:$port
    echo "--- roscore -p $port (try $try)" >>"$log"
    roscore -p "$port" >>"$log" 2>&1 &
    core=$!
    deadline=$((SECONDS + 60))
    while kill -0 "$core" 2>/dev/null; do
      rosparam list >/dev/null 2>&1 && return 0
      if [ "$SECONDS" -ge "$deadline" ]; then
        master_failure="the master (roscore -p $port) did not answer within 60 s: $(tail -n 2 "$log" | tr '\n' ' ')"
        return 1
      fi
      sleep 0.2
    done
  done
  master_failure="roscore exited 3 times: $(tail -n 2 "$log" | tr '\n' ' ')"
  return 1
}
