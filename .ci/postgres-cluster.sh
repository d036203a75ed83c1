#!/usr/bin/env bash
# A throwaway PostgreSQL cluster for a test run (the tests' REENACT_TEST_POSTGRES_URL):
#   postgres-cluster.sh start       creates and starts one under a new /tmp directory (a unix
#                                   socket there, no TCP port, trust authentication, fsync off,
#                                   PostGIS created in template1 so each test database has it)
#                                   and prints its connection string
#   postgres-cluster.sh stop URL    stops the cluster of that connection string and removes it
# Run as root, the server runs as the `postgres` user (PostgreSQL refuses root). Fails with a
# message on stderr where no PostgreSQL server with PostGIS is installed (deploy/install-deps.sh).
set -euo pipefail

bin=$(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -n 1)

as_owner() {
  if [ "$(id -u)" -eq 0 ]; then runuser -u postgres -- "$@"; else "$@"; fi
}

case "${1:-}" in
  start)
    if [ -z "$bin" ] || [ ! -x "$bin/initdb" ]; then
      echo "postgres-cluster: no PostgreSQL server in /usr/lib/postgresql" >&2
      exit 1
    fi
    dir=$(mktemp -d /tmp/reenact-ci-pg-XXXXXX)
    [ "$(id -u)" -eq 0 ] && chown postgres: "$dir"
    if ! as_owner "$bin/initdb" -D "$dir/data" -A trust -U reenact -E UTF8 --locale=C \
           --no-sync >"$dir/initdb.log" 2>&1 ||
       ! as_owner "$bin/pg_ctl" -D "$dir/data" -l "$dir/server.log" -w -t 60 \
           -o "-k $dir -p 5432 -c listen_addresses= -c fsync=off" start >/dev/null; then
      echo "postgres-cluster: the cluster in $dir did not start:" >&2
      tail -n 20 "$dir"/*.log >&2 || true
      exit 1
    fi
    url="host=$dir port=5432 user=reenact dbname=postgres"
    if ! psql -X -q "host=$dir port=5432 user=reenact dbname=template1" \
           -c "CREATE EXTENSION postgis" >&2; then
      echo "postgres-cluster: PostGIS is not installed for PostgreSQL ${bin%/bin}" >&2
      bash "$0" stop "$url"
      exit 1
    fi
    echo "$url"
    ;;
  stop)
    dir=$(sed -n 's/.*host=\([^ ]*\).*/\1/p' <<<"${2:-}")
    case "$dir" in
      /tmp/reenact-ci-pg-*) ;;
      *) echo "postgres-cluster: stop wants the connection string start printed" >&2; exit 1 ;;
    esac
    as_owner "$bin/pg_ctl" -D "$dir/data" -m fast -w stop >/dev/null 2>&1 || true
    rm -rf "$dir"
    ;;
  *)
    echo "usage: postgres-cluster.sh start | stop URL" >&2
    exit 2
    ;;
esac
