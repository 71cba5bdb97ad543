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

# The deploy tests' campaign: the small configuration (run.txtpb beside it)
# at two drags, runs c-d1 and c-d10.
write_two_drag_campaign() {  # FILE
  cat > "$1" <<'CAMPAIGN'
runs {
  name: "c"
  config: "run.txtpb"
  axes {
    values { label: "d1" }
    values { label: "d10" set: "model { physics { drag_normal: 10 } }" }
  }
}
CAMPAIGN
}

# Run c-d10 made alone: the small configuration RUN_CONFIG at drag 10, into
# STORE (with animat evolve from BIN).
run_d10_alone() {  # BIN RUN_CONFIG STORE
  local config="${3%.db}.txtpb"
  sed 's/^model { evaluation/model { physics { drag_normal: 10 } evaluation/' \
    "$2" > "$config"
  grep -q drag_normal "$config" || fail "no drag in the d10 configuration"
  "$1/animat" evolve --config "$config" --db "$3" --workers 1 \
    > "${3%.db}.log" 2>&1 || fail "the d10 reference run failed"
}

# Each store of the two-drag campaign in DIR equals its run made alone
# (the small configuration's REFERENCE, and REFERENCE_D10).
expect_two_drag_stores() {  # DIR REFERENCE REFERENCE_D10
  [ "$(digest "$1/c-d1.db")" = "$(digest "$2")" ] ||
    fail "the campaign's run c-d1 differs from the run made alone"
  [ "$(digest "$1/c-d10.db")" = "$(digest "$3")" ] ||
    fail "the campaign's run c-d10 differs from the run made alone"
}
