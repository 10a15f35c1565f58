#!/usr/bin/env bash
# A throwaway PostgreSQL for the tests: `start DIR PORT` makes a cluster in DIR (initdb,
# trust auth on loopback, fsync off) and starts it on 127.0.0.1:PORT; `stop DIR` stops it
# (fast: connections are cut), `resume DIR` starts a stopped one again on its port,
# `restart DIR` stops and starts it. Installs
# PostgreSQL from apt when its binaries are missing. PostgreSQL refuses to run as root:
# as root, the cluster runs as the `postgres` user (created with the package), which owns
# DIR. Prints nothing on success but the URL after `start`:
#   postgres://postgres@127.0.0.1:PORT/postgres
set -euo pipefail

bindir() {
    if command -v initdb >/dev/null 2>&1; then
        dirname "$(command -v initdb)"
        return
    fi
    local d
    d=$(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -1 || true)
    if [ -z "$d" ] && [ "$(id -u)" = 0 ]; then
        echo "postgres.sh: installing PostgreSQL (apt-get)" >&2
        (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq postgresql) >&2
        d=$(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -1 || true)
    fi
    [ -n "$d" ] || { echo "postgres.sh: no PostgreSQL binaries (initdb) found" >&2; exit 1; }
    echo "$d"
}

as_owner() {
    if [ "$(id -u)" = 0 ]; then
        runuser -u postgres -- "$@"
    else
        "$@"
    fi
}

# The server's settings: loopback only, no Unix socket, no fsync (tests only).
options() {
    echo "-h 127.0.0.1 -p $1 -k '' -c fsync=off -c synchronous_commit=off -c full_page_writes=off -c max_connections=300"
}

cmd=${1:?usage: postgres.sh start DIR PORT | stop DIR | restart DIR | resume DIR}
dir=${2:?data directory}
bin=$(bindir)

case "$cmd" in
start)
    port=${3:?port}
    mkdir -p "$dir"
    if [ "$(id -u)" = 0 ]; then
        id postgres >/dev/null 2>&1 || useradd --system --home-dir /var/lib/postgresql postgres
        chown postgres "$dir"
        # the postgres user must reach DIR through its parent
        chmod o+x "$(dirname "$dir")"
    fi
    if [ ! -f "$dir/PG_VERSION" ]; then
        as_owner "$bin/initdb" -D "$dir" -U postgres --auth=trust --no-sync -E UTF8 >"$dir.initdb.log" 2>&1 \
            || { cat "$dir.initdb.log" >&2; exit 1; }
    fi
    echo "$port" >"$dir.port"
    as_owner "$bin/pg_ctl" -D "$dir" -l "$dir/server.log" -w -t 60 -o "$(options "$port")" start >/dev/null
    echo "postgres://postgres@127.0.0.1:$port/postgres"
    ;;
resume)
    as_owner "$bin/pg_ctl" -D "$dir" -l "$dir/server.log" -w -t 60 -o "$(options "$(cat "$dir.port")")" start >/dev/null
    ;;
stop)
    as_owner "$bin/pg_ctl" -D "$dir" -m fast -w -t 60 stop >/dev/null
    ;;
restart)
    as_owner "$bin/pg_ctl" -D "$dir" -m fast -w -t 60 restart >/dev/null
    ;;
*)
    echo "usage: postgres.sh start DIR PORT | stop DIR | restart DIR | resume DIR" >&2
    exit 2
    ;;
esac
