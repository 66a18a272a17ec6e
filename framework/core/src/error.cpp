#include "geotandem/core/error.hpp"

namespace geotandem {

std::string format_error(const std::string& message, const ErrorContext& context, const std::string& hint) {
  // Built with append() rather than operator+ chains: GCC 12 at -O3 reports a false -Wrestrict
  // in the inlined string concatenation.
  std::string where = context.file;
  if (context.line) {
    where.append(":").append(std::to_string(*context.line));
    if (context.column) where.append(":").append(std::to_string(*context.column));
  }
  auto append = [&where](const std::string& part) {
    if (part.empty()) return;
    if (!where.empty()) where += ", ";
    where += part;
  };
  append(context.block);
  if (!context.worker.empty()) append(std::string("worker ").append(context.worker));

  std::string text = where;
  if (!text.empty()) text.append(": ");
  text.append(message);
  if (!hint.empty()) text.append(" (").append(hint).append(")");
  return text;
}

Error::Error(std::string message, ErrorContext context, std::string hint)
    : std::runtime_error(format_error(message, context, hint)), message_(std::move(message)),
      context_(std::move(context)), hint_(std::move(hint)) {}

void throw_with_note(const Error& e, const std::string& note) {
  if (dynamic_cast<const Cancelled*>(&e)) throw Cancelled();
  std::string message = e.message();
  message.append(note);
  if (dynamic_cast<const InvalidArgument*>(&e)) throw InvalidArgument(message, e.context(), e.hint());
  if (dynamic_cast<const IoError*>(&e)) throw IoError(message, e.context(), e.hint());
  if (dynamic_cast<const FormatError*>(&e)) throw FormatError(message, e.context(), e.hint());
  if (dynamic_cast<const DataError*>(&e)) throw DataError(message, e.context(), e.hint());
  throw Error(message, e.context(), e.hint());
}

Cancelled::Cancelled() : Error("operation cancelled", {}, "the work done before the cancel is kept") {}

} // namespace geotandem
