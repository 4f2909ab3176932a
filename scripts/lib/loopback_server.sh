# An alignset-server on a free loopback port, for the scripts that talk to a
# real one (quickstart, benchmarks, the package test). Source it, then:
#
#   start_loopback_server WAIT_S LOG COMMAND...
#     runs COMMAND (the server binary, or it behind taskset, and its flags)
#     with --listen 127.0.0.1:0 --port-file, its output appended to LOG. Port
#     0 lets the kernel pick a free port, so a server already on the default
#     port does not get in the way. Sets SERVER_PID and ADDR; returns 1, with
#     the log's tail on stderr, when the server exits or writes no port
#     within WAIT_S seconds.
#   stop_loopback_server
#     SIGTERM, waits for the exit, removes the port file; safe to call twice.

start_loopback_server() {
  local wait_s=$1 log=$2
  shift 2
  LOOPBACK_PORT_FILE=$(mktemp)
  "$@" --listen 127.0.0.1:0 --port-file "$LOOPBACK_PORT_FILE" >>"$log" 2>&1 &
  SERVER_PID=$!
  local i
  for ((i = 0; i < wait_s * 10; ++i)); do
    [ -s "$LOOPBACK_PORT_FILE" ] && break
    kill -0 "$SERVER_PID" 2>/dev/null || break
    sleep 0.1
  done
  if [ ! -s "$LOOPBACK_PORT_FILE" ]; then
    echo "alignset-server did not start (log $log):" >&2
    tail -n 40 "$log" >&2
    stop_loopback_server
    return 1
  fi
  ADDR="127.0.0.1:$(head -n 1 "$LOOPBACK_PORT_FILE")"
}

stop_loopback_server() {
  if [ -n "${SERVER_PID:-}" ]; then
    kill -TERM "$SERVER_PID" 2>/dev/null || true
    wait "$SERVER_PID" 2>/dev/null || true
  fi
  SERVER_PID=
  if [ -n "${LOOPBACK_PORT_FILE:-}" ]; then rm -f "$LOOPBACK_PORT_FILE"; fi
  LOOPBACK_PORT_FILE=
}
