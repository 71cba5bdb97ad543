// Tests only: the lineage store's database, to look at its tables and to
// damage them on purpose (an unreadable configuration, a failing trigger).
// Production code asks through Store's methods and master/lineage/
// queries.h; Store names this class a friend for the tests' sake.
#ifndef ANIMAT_TESTS_LINEAGE_STORE_TEST_PEER_H_
#define ANIMAT_TESTS_LINEAGE_STORE_TEST_PEER_H_

#include "master/lineage/sqlite.h"
#include "master/lineage/store.h"

namespace animat::lineage {

class StoreTestPeer {
 public:
  // The store's connection, owned by `store` and valid while it lives.
  static sql::Database& Database(Store& store) { return store.database(); }
};

}  // namespace animat::lineage

#endif  // ANIMAT_TESTS_LINEAGE_STORE_TEST_PEER_H_
