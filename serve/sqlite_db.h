// What the workbench's two SQLite stores (saved jobs, the machine queue) share: a prepared
// statement, and opening a database in the data directory with its schema.
#pragma once

#include <sqlite3.h>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace strand::serve::sqlite {

struct Statement {
  sqlite3_stmt* s = nullptr;
  Statement(sqlite3* db, const char* sql) {
    if (sqlite3_prepare_v2(db, sql, -1, &s, nullptr) != SQLITE_OK) {
      throw std::runtime_error(std::string("sqlite: ") + sqlite3_errmsg(db));
    }
  }
  ~Statement() { sqlite3_finalize(s); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  void bind(int i, const std::string& v) { sqlite3_bind_text(s, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT); }
  void bind(int i, std::int64_t v) { sqlite3_bind_int64(s, i, v); }
  void bind(int i, int v) { sqlite3_bind_int64(s, i, v); }
  // Binds `values` to the parameters 1, 2, ... in order.
  template <class... Values>
  void bind_all(const Values&... values) {
    int i = 0;
    (bind(++i, values), ...);
  }
  bool step() {
    const int rc = sqlite3_step(s);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw std::runtime_error(std::string("sqlite: ") + sqlite3_errmsg(sqlite3_db_handle(s)));
  }
  std::string text(int col) {
    const auto* p = sqlite3_column_text(s, col);
    return p ? std::string(reinterpret_cast<const char*>(p), static_cast<std::size_t>(sqlite3_column_bytes(s, col))) : "";
  }
  std::int64_t integer(int col) { return sqlite3_column_int64(s, col); }
};

// Opens (creates) the database at `path`, waits up to 5 s for a lock, runs `schema`; throws
// InputError naming --data and `what` ("the queue") when it cannot.
sqlite3* open(const std::string& path, const char* schema, const std::string& what);

}  // namespace strand::serve::sqlite
