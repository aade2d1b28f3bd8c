// Opening the workbench's SQLite databases (see sqlite_db.h).
#include "serve/sqlite_db.h"

#include "slicer/input_error.h"

namespace strand::serve::sqlite {

sqlite3* open(const std::string& path, const char* schema, const std::string& what) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX,
                      nullptr) != SQLITE_OK) {
    const std::string why = db ? sqlite3_errmsg(db) : "out of memory";
    sqlite3_close(db);
    throw InputError("--data: cannot open " + path + " (" + why + ")");
  }
  sqlite3_busy_timeout(db, 5000);
  char* err = nullptr;
  if (sqlite3_exec(db, schema, nullptr, nullptr, &err) != SQLITE_OK) {
    const std::string why = err ? err : "?";
    sqlite3_free(err);
    sqlite3_close(db);
    throw InputError("--data: cannot use " + path + what + " (" + why + ")");
  }
  return db;
}

}  // namespace strand::serve::sqlite
