#include "src/formats/json_file.h"

#include <algorithm>
#include <string>
#include <vector>

#include "src/core/error.h"
#include "src/formats/file_reading.h"

namespace rsl {

namespace {

using Json = nlohmann::json;

// A SAX pass that only tracks where it is (the key path) and records the
// first error, so the message can say which key held the bad value.
class JsonLocator final : public nlohmann::json_sax<Json> {
public:
    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override {
        value();
        path_.push_back({"", -1});
        return true;
    }
    bool key(string_t& name) override {
        path_.back().key = name;
        return true;
    }
    bool end_object() override {
        path_.pop_back();
        return true;
    }
    bool start_array(std::size_t) override {
        value();
        path_.push_back({"", 0});
        return true;
    }
    bool end_array() override {
        path_.pop_back();
        return true;
    }
    bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) override {
        byte = position;
        message = e.what();
        where = key_path();
        return false;
    }

    size_t byte = 0;
    std::string message, where;

private:
    struct Level {
        std::string key;  // in an object: the key being read
        int index;        // in an array: elements begun so far (−1 in objects)
    };
    // Called before each value: advances the enclosing array's index.
    bool value() {
        if (!path_.empty() && path_.back().index >= 0) ++path_.back().index;
        return true;
    }
    // Enclosing arrays hold an open container at their last counted element;
    // the innermost one failed on the element after its last counted one.
    std::string key_path() const {
        std::string out;
        for (size_t k = 0; k < path_.size(); ++k) {
            const Level& level = path_[k];
            if (level.index >= 0)
                out += fmt::format("[{}]", k + 1 == path_.size() ? level.index : level.index - 1);
            else if (!level.key.empty())
                out += (out.empty() ? "" : ".") + level.key;
        }
        return out;
    }
    std::vector<Level> path_;
};

}  // namespace

Json parse_json_text(const std::filesystem::path& path, std::string_view text) {
    try {
        return Json::parse(text.begin(), text.end());
    } catch (const Json::exception&) {
        // Parse again, only to learn where: the locator sees the same error.
    }
    JsonLocator locator;
    if (Json::sax_parse(text.begin(), text.end(), &locator))
        throw_file_error(path, "invalid JSON (the parser failed, its locating pass did not)");
    // nlohmann reports a byte offset (one past the bad token); people need a line and column.
    const size_t byte = std::min(locator.byte, text.size());
    const size_t line = 1 + std::count(text.begin(), text.begin() + byte, '\n');
    const size_t line_start = byte == 0 ? std::string_view::npos : text.rfind('\n', byte - 1);
    const size_t column = line_start == std::string_view::npos ? byte : byte - line_start - 1;
    if (locator.where.empty())
        throw_file_error(path, "line {}, column {}: invalid JSON: {}", line, column, locator.message);
    throw_file_error(path, "line {}, column {}, key {}: invalid JSON: {}", line, column, locator.where,
                     locator.message);
}

Json read_json_file(const std::filesystem::path& path) {
    return parse_json_text(path, read_bounded_file(path, kMaxJsonFileBytes, "a JSON file"));
}

}  // namespace rsl
