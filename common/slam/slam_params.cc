#include "common/slam/slam_params.h"

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/text_format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "common/io/file_bytes.h"
#include "common/io/text_fields.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

namespace pb = google::protobuf;

// Sets every unset singular field of `message` to its declared default, recursing into its
// message fields (into `only` alone, when given): a parameter message then says what a run used
// without the proto at hand.
void SetDefaults(pb::Message& message, const pb::FieldDescriptor* only = nullptr) {
  const pb::Descriptor& d = *message.GetDescriptor();
  const pb::Reflection& r = *message.GetReflection();
  for (int i = 0; i < d.field_count(); ++i) {
    const pb::FieldDescriptor* f = d.field(i);
    if (f->is_repeated()) continue;
    if (f->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE) {
      if (only == nullptr || f == only) SetDefaults(*r.MutableMessage(&message, f));
      continue;
    }
    if (r.HasField(message, f)) continue;
    switch (f->cpp_type()) {
      case pb::FieldDescriptor::CPPTYPE_DOUBLE:
        r.SetDouble(&message, f, f->default_value_double());
        break;
      case pb::FieldDescriptor::CPPTYPE_UINT32:
        r.SetUInt32(&message, f, f->default_value_uint32());
        break;
      case pb::FieldDescriptor::CPPTYPE_UINT64:
        r.SetUInt64(&message, f, f->default_value_uint64());
        break;
      case pb::FieldDescriptor::CPPTYPE_BOOL:
        r.SetBool(&message, f, f->default_value_bool());
        break;
      case pb::FieldDescriptor::CPPTYPE_STRING:
        r.SetString(&message, f, f->default_value_string());
        break;
      default:
        throw Error("SLAM parameter " + f->full_name() + ": a type parameters do not take");
    }
  }
}

// The message field of SlamParams that holds `method`'s parameters.
const pb::FieldDescriptor& MethodField(const std::string& method) {
  const pb::FieldDescriptor* f = proto::SlamParams::descriptor()->FindFieldByName(method);
  if (f == nullptr || f->cpp_type() != pb::FieldDescriptor::CPPTYPE_MESSAGE) {
    throw Error("method '" + method + "' is not a SLAM method (" + SlamMethodList() + ")");
  }
  return *f;
}

// Sets one scalar field from its text; false when the text is not a value of its type.
bool SetScalar(pb::Message& m, const pb::FieldDescriptor& f, std::string_view text) {
  const pb::Reflection& r = *m.GetReflection();
  switch (f.cpp_type()) {
    case pb::FieldDescriptor::CPPTYPE_DOUBLE: {
      const std::optional<double> v = ParseDouble(text);
      if (!v || !std::isfinite(*v)) return false;
      r.SetDouble(&m, &f, *v);
      return true;
    }
    case pb::FieldDescriptor::CPPTYPE_UINT32: {
      const std::optional<std::size_t> v = ParseCount(text);
      if (!v || *v > std::numeric_limits<std::uint32_t>::max()) return false;
      r.SetUInt32(&m, &f, static_cast<std::uint32_t>(*v));
      return true;
    }
    case pb::FieldDescriptor::CPPTYPE_UINT64: {
      const std::optional<std::size_t> v = ParseCount(text);
      if (!v) return false;
      r.SetUInt64(&m, &f, *v);
      return true;
    }
    case pb::FieldDescriptor::CPPTYPE_BOOL:
      if (text != "true" && text != "1" && text != "false" && text != "0") return false;
      r.SetBool(&m, &f, text == "true" || text == "1");
      return true;
    case pb::FieldDescriptor::CPPTYPE_STRING:
      r.SetString(&m, &f, std::string(text));
      return true;
    default:
      return false;
  }
}

// The field a dotted path names below `message`, and the message that holds it (created on the
// way); nullopt when no field has that path or it names a message.
std::optional<std::pair<pb::Message*, const pb::FieldDescriptor*>> FindPath(pb::Message& message,
                                                                            std::string_view path) {
  pb::Message* at = &message;
  while (true) {
    const std::size_t dot = path.find('.');
    const pb::FieldDescriptor* f =
        at->GetDescriptor()->FindFieldByName(std::string(path.substr(0, dot)));
    if (f == nullptr || f->is_repeated()) return std::nullopt;
    const bool is_message = f->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE;
    if (dot == std::string_view::npos) {
      if (is_message) return std::nullopt;
      return std::pair{at, f};
    }
    if (!is_message) return std::nullopt;
    at = at->GetReflection()->MutableMessage(at, f);
    path.remove_prefix(dot + 1);
  }
}

// Collects the first error TextFormat reports, with its line.
class FirstError : public pb::io::ErrorCollector {
 public:
  void AddError(int line, pb::io::ColumnNumber column, const std::string& message) override {
    if (text_.empty()) {
      text_ = "line " + std::to_string(line + 1) + ", column " + std::to_string(column + 1) + ": " +
              message;
    }
  }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

}  // namespace

std::vector<std::string> SlamMethodNames() {
  std::vector<std::string> names;
  const pb::Descriptor& d = *proto::SlamParams::descriptor();
  for (int i = 0; i < d.field_count(); ++i) {
    if (d.field(i)->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE) {
      names.push_back(d.field(i)->name());
    }
  }
  return names;
}

std::string SlamMethodList() {
  std::string list;
  for (const std::string& name : SlamMethodNames()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

void CheckOneMethodsParams(const proto::SlamParams& params) {
  const pb::FieldDescriptor& method = MethodField(params.method());
  const pb::Reflection& r = *params.GetReflection();
  for (const std::string& other : SlamMethodNames()) {
    const pb::FieldDescriptor& f = MethodField(other);
    if (&f != &method && r.HasField(params, &f)) {
      throw Error("parameters of method " + other + " given to a run of method " + params.method());
    }
  }
}

proto::SlamParams WithDefaults(const proto::SlamParams& params) {
  proto::SlamParams complete = params;
  SetDefaults(complete, &MethodField(complete.method()));
  if (!params.has_log()) complete.clear_log();  // an input, not a parameter with a default
  return complete;
}

void SetSlamParam(proto::SlamParams& params, std::string_view name, std::string_view text) {
  // The method's own parameters first, so that its message's prefix may be left out.
  const pb::FieldDescriptor& method = MethodField(params.method());
  const pb::Reflection& reflection = *params.GetReflection();
  const bool had_own = reflection.HasField(params, &method);
  pb::Message& own = *reflection.MutableMessage(&params, &method);
  auto found = FindPath(own, name);
  if (!found) {
    // Looking the name up made the method's message; a parameter from the top (the method
    // itself, say) leaves it as it was, so that no other method's parameters seem given.
    if (!had_own) reflection.ClearField(&params, &method);
    found = FindPath(params, name);
  }
  if (!found) {
    throw Error("no SLAM parameter is named '" + std::string(name) +
                "' (docs/configuration.md lists them)");
  }
  const auto [message, field] = *found;
  if (field->name() == "log" && message == &params) {
    throw Error("the log is not a parameter: give it with --log");
  }
  if (!SetScalar(*message, *field, text)) {
    throw Error(std::string(name) + ": '" + std::string(text) + "' is not a " +
                field->cpp_type_name() + " value");
  }
}

const pb::FieldDescriptor& SlamParamField(std::string_view name) {
  proto::SlamParams scratch;
  const auto found = FindPath(scratch, name);
  if (!found) throw Error("no SLAM parameter is named '" + std::string(name) + "'");
  return *found->second;
}

std::string SlamParamText(const proto::SlamParams& params, std::string_view name) {
  proto::SlamParams copy = params;
  const auto found = FindPath(copy, name);
  if (!found) throw Error("no SLAM parameter is named '" + std::string(name) + "'");
  std::string text;
  pb::TextFormat::PrintFieldValueToString(*found->first, found->second, -1, &text);
  return text;
}

proto::SlamParams ReadSlamParamsFile(const std::string& path) {
  const std::string text = ReadFileBytes(path);
  proto::SlamParams params;
  FirstError errors;
  pb::TextFormat::Parser parser;
  parser.RecordErrorsTo(&errors);
  if (!parser.ParseFromString(text, &params)) {
    throw Error(path + ": " +
                (errors.text().empty() ? "not a SLAM parameter file" : errors.text()));
  }
  if (params.has_log()) {
    throw Error(path + ": the log is not a parameter: give it with --log");
  }
  return params;
}

std::string SlamParamsText(const proto::SlamParams& params) {
  std::string text;
  pb::TextFormat::Printer printer;
  printer.PrintToString(params, &text);
  return text;
}

}  // namespace evoslam
