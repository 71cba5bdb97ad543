# Shared by the deployment tests (sourced): a small run configuration,
# waiting on a store's progress, and a digest of everything a run decided.
# Needs sqlite3; `fail MESSAGE` must be defined by the test.

# Writes a run configuration small enough for CI and long enough to
# interrupt a few times (a generation takes a fraction of a second).
write_small_config() {
  cat > "$1" <<'CONF'
model { evaluation { motion_steps: 1200 } }
evolution {
  seed: 7
  population: 40
  generations: 24
  elite: 2
}
CONF
}
small_config_generations=24

generations_done() {  # completed generations in the store, 0 if none yet
  sqlite3 "file:$1?mode=ro" \
    "SELECT COUNT(*) FROM generations WHERE completed_at IS NOT NULL" \
    2>/dev/null || echo 0
}

wait_generations() {  # STORE N: until the store has N completed generations
  for _ in $(seq 3000); do
    [ "$(generations_done "$1")" -ge "$2" ] && return 0
    sleep 0.1
  done
  fail "the store did not reach $2 completed generations"
}

run_state() {  # "running" or "finished"
  sqlite3 "file:$1?mode=ro" "SELECT state FROM runs"
}

# Everything the run decided: individuals, parents, evaluations (to the
# bit) and generations; wall times, workers and timestamps aside.
digest() {
  sqlite3 "file:$1?mode=ro" "
    SELECT id, generation, operators, hex(genome), status, reason,
           quote(fitness), cells, steps, state_hash, springs, chambers,
           skin_edges, quote(spread_major), quote(spread_minor)
    FROM individuals
    ORDER BY id;
    SELECT * FROM parents ORDER BY child, position;
    SELECT generation, id, rank FROM members ORDER BY generation, id;
    SELECT generation, size, evaluated, failed, best_id,
           quote(best_fitness), quote(mean_fitness), quote(median_fitness)
    FROM generations ORDER BY generation;" | sha256sum
}
