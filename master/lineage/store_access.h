// The lineage store's database, for the query functions of master/lineage/
// (queries.cc) only: code outside master/lineage/ asks its questions
// through those functions and Store's methods, never in SQL.
#ifndef ANIMAT_MASTER_LINEAGE_STORE_ACCESS_H_
#define ANIMAT_MASTER_LINEAGE_STORE_ACCESS_H_

#include "master/lineage/sqlite.h"
#include "master/lineage/store.h"

namespace animat::lineage {

class StoreAccess {
 public:
  // The store's connection, owned by `store` and valid while it lives;
  // not thread-safe, like the Store.
  static sql::Database& Database(Store& store) { return store.database(); }
};

}  // namespace animat::lineage

#endif  // ANIMAT_MASTER_LINEAGE_STORE_ACCESS_H_
