#ifndef EVOSLAM_COORDINATOR_SQLITE_H_
#define EVOSLAM_COORDINATOR_SQLITE_H_

#include <sqlite3.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace evoslam {

// A prepared statement: bind, step, read columns, reset. Errors throw Error naming the SQL.
class Statement {
 public:
  Statement(sqlite3* db, std::string_view sql);

  Statement& Bind(int index, std::int64_t value);
  Statement& Bind(int index, double value);
  Statement& Bind(int index, std::string_view text);
  Statement& BindBlob(int index, std::string_view bytes);
  // Advances to the next row; false when there is none.
  bool Step();
  // Runs a statement that returns no rows, then resets it for reuse.
  void Run();
  void Reset();

  std::int64_t Int(int column) const;
  double Real(int column) const;
  std::string Text(int column) const;  // also reads blobs, byte for byte

 private:
  struct Finalize {
    void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
  };
  sqlite3* db_;
  std::string sql_;
  std::unique_ptr<sqlite3_stmt, Finalize> stmt_;
};

// One blob of one row, open for writing in place (sqlite3_blob). A blob keeps its size: one made
// with zeroblob(n) is filled piece by piece, so a large one is never in memory whole. It must be
// closed (destroyed) before the transaction it was opened in commits.
class Blob {
 public:
  void Write(std::uint64_t offset, std::string_view bytes);

 private:
  friend class Database;
  struct Close {
    void operator()(sqlite3_blob* b) const { sqlite3_blob_close(b); }
  };
  Blob(sqlite3* db, sqlite3_blob* blob, std::string what)
      : db_(db), blob_(blob), what_(std::move(what)) {}
  sqlite3* db_;
  std::unique_ptr<sqlite3_blob, Close> blob_;
  std::string what_;
};

// One connection to a database file. Opened in WAL mode with full synchronisation: a committed
// transaction survives the process being killed, or the machine losing power.
class Database {
 public:
  explicit Database(const std::filesystem::path& path);

  void Execute(std::string_view sql);  // statements without parameters or results
  Statement Prepare(std::string_view sql) { return Statement(db_.get(), sql); }
  std::int64_t LastInsertId() const { return sqlite3_last_insert_rowid(db_.get()); }
  // Rows changed by the last INSERT, UPDATE or DELETE.
  int Changes() const { return sqlite3_changes(db_.get()); }
  // The blob in `column` of `table`'s row `row`, opened for writing.
  Blob OpenBlob(const char* table, const char* column, std::int64_t row);

  // Runs body inside BEGIN IMMEDIATE ... COMMIT; rolls back if it throws.
  template <typename Body>
  void Transaction(Body body) {
    Execute("BEGIN IMMEDIATE");
    try {
      body();
    } catch (...) {
      Execute("ROLLBACK");
      throw;
    }
    Execute("COMMIT");
  }

 private:
  struct Close {
    void operator()(sqlite3* db) const { sqlite3_close_v2(db); }
  };
  std::filesystem::path path_;
  std::unique_ptr<sqlite3, Close> db_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_SQLITE_H_
