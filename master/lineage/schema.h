// The lineage store's schema, its version, and the migrations that bring an
// older store up to date (docs/lineage.md describes every table and view).
#ifndef ANIMAT_MASTER_LINEAGE_SCHEMA_H_
#define ANIMAT_MASTER_LINEAGE_SCHEMA_H_

#include "common/base/status.h"
#include "master/lineage/sqlite.h"

namespace animat::lineage {

// The schema this build writes (PRAGMA user_version).
inline constexpr int kSchemaVersion = 10;

// The schema version of `db` (its PRAGMA user_version; 0 for a database
// that is no lineage store): the one place it is read. Fails only on an
// SQLite error, naming the file.
Result<int> SchemaVersion(sql::Database& db);

// Brings `db` from its user_version to `target` (tests ask for older
// versions), one migration at a time, each in its own transaction. Refuses
// a store written by a newer build (a higher version), saying both
// versions; does nothing to a store already at `target` or above.
Status Migrate(sql::Database& db, int target = kSchemaVersion);

}  // namespace animat::lineage

#endif  // ANIMAT_MASTER_LINEAGE_SCHEMA_H_
