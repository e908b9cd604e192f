#pragma once
// One table of names per token enum: the single place an enum's values are
// spelt, from which it is parsed, printed and listed. An enum takes part by
// specialising TokenTable with a `names` array, in the header that declares
// it; its first entry is what tokenName gives a value outside the table (a
// cast integer). Settings (plan/SettingTokens.h), curve and primvar tokens,
// colour spaces and the tools' options all use it, so a value is spelt once
// and a misspelt one does not compile.

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace hdhair {

template <typename Enum>
struct TokenName {
    Enum value;
    const char* name;
};

// Specialised per enum:
//   template <> struct TokenTable<Fruit> {
//       static constexpr std::array<TokenName<Fruit>, 2> names{{{Fruit::Apple, "apple"}, {Fruit::Pear, "pear"}}};
//   };
template <typename Enum>
struct TokenTable;

// Whether Enum has a table.
template <typename Enum, typename = void>
struct HasTokenTable : std::false_type {};
template <typename Enum>
struct HasTokenTable<Enum, std::void_t<decltype(TokenTable<Enum>::names)>> : std::true_type {};

template <typename Enum>
const char* tokenName(Enum value) {
    for (const TokenName<Enum>& entry : TokenTable<Enum>::names)
        if (entry.value == value) return entry.name;
    return TokenTable<Enum>::names[0].name;
}

// Sets *out and returns true when `text` is one of Enum's names, exactly
// (tokens are case-sensitive, as USD's are).
template <typename Enum>
bool parseToken(std::string_view text, Enum* out) {
    for (const TokenName<Enum>& entry : TokenTable<Enum>::names)
        if (text == entry.name) {
            *out = entry.value;
            return true;
        }
    return false;
}

// Every name, in the table's order (the order --help-settings lists them).
template <typename Enum>
std::vector<std::string> tokenNames() {
    std::vector<std::string> names;
    for (const TokenName<Enum>& entry : TokenTable<Enum>::names) names.emplace_back(entry.name);
    return names;
}

// "a, b or c", for error messages.
template <typename Enum>
std::string tokenChoices() {
    const auto& names = TokenTable<Enum>::names;
    std::string text;
    for (size_t i = 0; i < names.size(); ++i)
        text += std::string(i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i].name;
    return text;
}

// toString for every enum with a table: found by argument-dependent lookup
// for enums in namespace hdhair, and preferred over nothing else (an enum
// with a table has no hand-written toString).
template <typename Enum, typename = std::enable_if_t<HasTokenTable<Enum>::value>>
const char* toString(Enum value) {
    return tokenName(value);
}

}  // namespace hdhair
