// libFuzzer's mutation hooks, shared by the fuzz targets: an input that parses as JSON is mutated
// structurally (json_mutator.hpp) and serialised again; one that does not parse, one in eight
// that does (the parser's and the readers' refusals of broken text stay covered), and a mutation
// whose result would not fit libFuzzer's maximum length get libFuzzer's own byte mutations.

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "format_words.hpp"
#include "json_mutator.hpp"

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t max_size);

namespace {

using nlohmann::json;

std::optional<json> parse(const uint8_t* data, size_t size) {
  json document = json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded()) return std::nullopt;
  return document;
}

/// The document as compact JSON in `out`; 0 when it does not fit in `max_size` bytes. A string
/// cut inside a UTF-8 sequence is written with U+FFFD in its place.
size_t serialise(const json& document, uint8_t* out, size_t max_size) {
  const std::string text = document.dump(-1, ' ', false, json::error_handler_t::replace);
  if (text.empty() || text.size() > max_size) return 0;
  std::memcpy(out, text.data(), text.size());
  return text.size();
}

}  // namespace

extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t max_size, unsigned int seed) {
  if (seed % 8 == 0) return LLVMFuzzerMutate(data, size, max_size);
  const std::optional<json> document = parse(data, size);
  if (!document) return LLVMFuzzerMutate(data, size, max_size);
  tsm::fuzz::JsonMutator mutator(seed, tsm::fuzz::format_words());
  for (int attempt = 0; attempt < 4; ++attempt) {
    json mutated = *document;
    mutator.mutate(mutated);
    if (const size_t written = serialise(mutated, data, max_size)) return written;
  }
  return LLVMFuzzerMutate(data, size, max_size);
}

extern "C" size_t LLVMFuzzerCustomCrossOver(const uint8_t* data1, size_t size1, const uint8_t* data2, size_t size2,
                                            uint8_t* out, size_t max_out_size, unsigned int seed) {
  std::optional<json> document = parse(data1, size1);
  const std::optional<json> donor = parse(data2, size2);
  if (!document || !donor) return 0;  // libFuzzer then mutates otherwise
  tsm::fuzz::JsonMutator(seed, tsm::fuzz::format_words()).cross_over(*document, *donor);
  return serialise(*document, out, max_out_size);
}
