#include "coordinator/sqlite.h"

#include <limits>
#include <string>

#include "common/util/error.h"

namespace evoslam {
namespace {

[[noreturn]] void Fail(sqlite3* db, const std::string& what) {
  throw Error(what + ": " + (db ? sqlite3_errmsg(db) : "out of memory"));
}

}  // namespace

Statement::Statement(sqlite3* db, std::string_view sql) : db_(db), sql_(sql) {
  sqlite3_stmt* stmt = nullptr;
  if (sqlite3_prepare_v2(db, sql_.c_str(), static_cast<int>(sql_.size()), &stmt, nullptr) !=
      SQLITE_OK)
    Fail(db, "database: cannot prepare '" + sql_ + "'");
  stmt_.reset(stmt);
}

Statement& Statement::Bind(int index, std::int64_t value) {
  if (sqlite3_bind_int64(stmt_.get(), index, value) != SQLITE_OK) Fail(db_, "database: bind");
  return *this;
}

Statement& Statement::Bind(int index, double value) {
  if (sqlite3_bind_double(stmt_.get(), index, value) != SQLITE_OK) Fail(db_, "database: bind");
  return *this;
}

Statement& Statement::Bind(int index, std::string_view text) {
  if (sqlite3_bind_text(stmt_.get(), index, text.data(), static_cast<int>(text.size()),
                        SQLITE_TRANSIENT) != SQLITE_OK)
    Fail(db_, "database: bind");
  return *this;
}

Statement& Statement::BindBlob(int index, std::string_view bytes) {
  if (sqlite3_bind_blob64(stmt_.get(), index, bytes.data(), bytes.size(), SQLITE_TRANSIENT) !=
      SQLITE_OK)
    Fail(db_, "database: bind");
  return *this;
}

bool Statement::Step() {
  const int rc = sqlite3_step(stmt_.get());
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  Fail(db_, "database: '" + sql_ + "'");
}

void Statement::Run() {
  Step();
  Reset();
}

void Statement::Reset() {
  sqlite3_reset(stmt_.get());
  sqlite3_clear_bindings(stmt_.get());
}

std::int64_t Statement::Int(int column) const { return sqlite3_column_int64(stmt_.get(), column); }

double Statement::Real(int column) const { return sqlite3_column_double(stmt_.get(), column); }

std::string Statement::Text(int column) const {
  const void* data = sqlite3_column_blob(stmt_.get(), column);
  const int size = sqlite3_column_bytes(stmt_.get(), column);
  return data ? std::string(static_cast<const char*>(data), static_cast<std::size_t>(size))
              : std::string();
}

Database::Database(const std::filesystem::path& path) : path_(path) {
  sqlite3* db = nullptr;
  const int rc =
      sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
  db_.reset(db);
  if (rc != SQLITE_OK) Fail(db, "cannot open database " + path.string());
  // Another process holding the file (a second coordinator) makes us wait briefly, then fail.
  sqlite3_busy_timeout(db, 5000);
  Execute("PRAGMA journal_mode = WAL");
  Execute("PRAGMA synchronous = FULL");
  Execute("PRAGMA foreign_keys = ON");
}

void Blob::Write(std::uint64_t offset, std::string_view bytes) {
  if (offset + bytes.size() > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
    throw Error(what_ + ": past 2 GiB");
  }
  if (sqlite3_blob_write(blob_.get(), bytes.data(), static_cast<int>(bytes.size()),
                         static_cast<int>(offset)) != SQLITE_OK) {
    Fail(db_, what_);
  }
}

Blob Database::OpenBlob(const char* table, const char* column, std::int64_t row) {
  std::string what = "database: writing " + std::string(table) + "." + column;
  sqlite3_blob* blob = nullptr;  // left null when the open fails
  if (sqlite3_blob_open(db_.get(), "main", table, column, row, 1, &blob) != SQLITE_OK) {
    Fail(db_.get(), what);
  }
  return Blob(db_.get(), blob, std::move(what));
}

void Database::Execute(std::string_view sql) {
  char* message = nullptr;
  const std::string statement(sql);
  if (sqlite3_exec(db_.get(), statement.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    const std::string text = message ? message : "unknown error";
    sqlite3_free(message);
    throw Error("database " + path_.string() + ": '" + statement + "': " + text);
  }
}

}  // namespace evoslam
