#include "hdHair/usda/LayerParser.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <system_error>

#include "hdHair/base/InputError.h"
#include "hdHair/usda/Tokenizer.h"

namespace hdhair::usda::detail {

namespace {

constexpr int kMaxNesting = 200;  // prims, dictionaries, lists: deeper input is rejected, not a stack overflow

bool parseDoubleText(std::string_view text, double& out) {
    if (text == "inf") { out = std::numeric_limits<double>::infinity(); return true; }
    if (text == "-inf") { out = -std::numeric_limits<double>::infinity(); return true; }
    if (text == "nan" || text == "-nan") { out = std::numeric_limits<double>::quiet_NaN(); return true; }
    if (text.empty()) return false;
    const char* begin = text.data();
    const char* end = begin + text.size();
    auto result = std::from_chars(begin, end, out);
    if (result.ptr != end) return false;
    if (result.ec == std::errc()) return true;
    if (result.ec == std::errc::result_out_of_range) {
        // 1e999 -> inf, 1e-999 -> 0, as strtod does.
        std::string copy(text);
        out = std::strtod(copy.c_str(), nullptr);
        return true;
    }
    return false;
}

bool isValidPrimName(const std::string& name) {
    if (name.empty()) return false;
    for (size_t i = 0; i < name.size(); ++i) {
        unsigned char c = static_cast<unsigned char>(name[i]);
        bool alpha = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c >= 0x80;
        bool digit = c >= '0' && c <= '9';
        if (!(alpha || (digit && i > 0))) return false;
    }
    return true;
}

// The value type of the metadata fields the reader knows; "" = untyped.
const char* knownMetadataType(const std::string& key) {
    static const std::pair<const char*, const char*> table[] = {
        {"kind", "token"},
        {"active", "bool"},
        {"hidden", "bool"},
        {"instanceable", "bool"},
        {"interpolation", "token"},
        {"elementSize", "int"},
        {"connectability", "token"},
        {"colorSpace", "token"},
        {"renderType", "token"},
        {"allowedTokens", "token[]"},
        {"doc", "string"},
        {"documentation", "string"},
        {"comment", "string"},
        {"displayName", "string"},
        {"displayGroup", "string"},
        {"defaultPrim", "token"},
        {"upAxis", "token"},
        {"metersPerUnit", "double"},
        {"kilogramsPerUnit", "double"},
        {"startTimeCode", "double"},
        {"endTimeCode", "double"},
        {"timeCodesPerSecond", "double"},
        {"framesPerSecond", "double"},
        {"customData", "dictionary"},
        {"customLayerData", "dictionary"},
        {"assetInfo", "dictionary"},
        {"sdrMetadata", "dictionary"},
        {"variants", "dictionary"},
    };
    for (const auto& entry : table) {
        if (key == entry.first) return entry.second;
    }
    return "";
}

void checkHeader(std::string_view text, const std::string& identifier) {
    auto failAt = [&identifier](int column, const std::string& message) {
        throw InputError(identifier + ":1:" + std::to_string(column) + ": " + message);
    };
    if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    if (text.substr(0, 8) == "PXR-USDC") {
        failAt(1, "this is a binary usdc layer; the embedded reader reads only text .usda "
                        "(convert it with 'usdcat in.usd -o out.usda')");
    }
    if (text.substr(0, 2) == "PK") {
        failAt(1, "this is a usdz package; the embedded reader reads only text .usda");
    }
    if (text.substr(0, 5) != "#usda") {
        size_t end = text.find('\n');
        std::string_view first = text.substr(0, std::min<size_t>(end == std::string_view::npos ? text.size() : end, 20));
        failAt(1, "expected the '#usda 1.0' header on the first line, found " +
                      (first.empty() ? std::string("end of file") : "'" + std::string(first) + "'"));
    }
    size_t pos = 5;
    size_t lineEnd = text.find('\n');
    if (lineEnd == std::string_view::npos) lineEnd = text.size();
    while (pos < lineEnd && (text[pos] == ' ' || text[pos] == '\t')) ++pos;
    size_t versionEnd = pos;
    while (versionEnd < lineEnd && text[versionEnd] != ' ' && text[versionEnd] != '\t' && text[versionEnd] != '\r') {
        ++versionEnd;
    }
    std::string_view version = text.substr(pos, versionEnd - pos);
    if (version != "1.0") {
        failAt(static_cast<int>(pos) + 1,
                  version.empty() ? std::string("expected the version '1.0' after '#usda'")
                                  : "unsupported usda version '" + std::string(version) + "' (expected '1.0')");
    }
}

class Parser {
public:
    Parser(std::string_view text, const std::string& identifier, const std::string& directory)
        : text_(text), tok_(text, identifier), directory_(directory) {}

    std::unique_ptr<Layer> run();

private:
    struct DepthGuard {
        Parser& parser;
        DepthGuard(Parser& owner, const Token& at) : parser(owner) {
            if (++parser.depth_ > kMaxNesting) {
                parser.tok_.fail(at, "nesting deeper than " + std::to_string(kMaxNesting) + " levels");
            }
        }
        ~DepthGuard() { --parser.depth_; }
        DepthGuard(const DepthGuard&) = delete;
        DepthGuard& operator=(const DepthGuard&) = delete;
    };

    // --- helpers ---
    const Token& peek() const { return tok_.peek(); }
    Token next() { return tok_.next(); }
    [[noreturn]] void fail(const Token& at, const std::string& message) const { tok_.fail(at, message); }
    static std::string found(const Token& t) { return ", found " + Tokenizer::describe(t); }
    std::string at(const Token& t) const { return std::to_string(t.line) + ":" + std::to_string(t.column); }
    SourceLocation location(const Token& t) const { return SourceLocation{tok_.identifier(), t.line, t.column}; }
    Token expectPunct(char punct, const std::string& context) {
        if (!peek().is(punct)) fail(peek(), std::string("expected '") + punct + "' " + context + found(peek()));
        return next();
    }
    // A statement ends at a new line, '}', ';' or the end of the text.
    bool atStatementEnd() const {
        const Token& t = peek();
        return t.kind == TokenKind::End || t.is('}') || t.is(';') || t.newlineBefore;
    }
    void endStatement(const std::string& what) {
        if (!atStatementEnd()) fail(peek(), "expected a new line after " + what + found(peek()));
    }
    static Value stringValue(std::string text) {
        Value value;
        value.typeName = "string";
        value.strings.push_back(std::move(text));
        return value;
    }

    // --- values ---
    double number(const Token& t, const std::string& what, bool allowBool);
    void parseScalar(const std::string& scalar, Value& out, const std::string& what);
    void parseTuple(int count, const std::string& scalar, Value& out, const std::string& what);
    Value parseTyped(const std::string& scalar, bool isArray, const std::string& what);
    Value parseTypedName(const std::string& typeName, const std::string& what) {
        std::string scalar = scalarTypeNameOf(typeName);
        return parseTyped(scalar, scalar != typeName, what);
    }
    Value parseGeneric(const std::string& what);
    Value identifierValue(const Token& t, const std::string& what);
    Value parseGenericTuple(const std::string& what);
    Value parseGenericList(const Token& open, const std::string& what);
    static Value arrayOrList(std::vector<Value> elements);
    Value parseDictionary(const std::string& what);
    Value parseMetadataValue(const std::string& key, const std::string& what);
    template <class ReadItem>
    void parseCounted(int count, const char* nouns, const std::string& scalar, const std::string& what,
                      ReadItem&& readItem);
    template <class ReadItem>
    void parseItemsUntil(char close, const char* where, const std::string& what, ReadItem&& readItem);
    template <class ReadItem>
    void parseListOpItems(const char* where, const std::string& what, ReadItem&& readItem);
    std::vector<std::string> parseTokenList(TokenKind kind, std::string (*decode)(const Token&), const char* item,
                                            const char* itemOrList, const char* where, const std::string& what);
    std::vector<std::string> parsePathList(const std::string& what) {
        return parseTokenList(TokenKind::Path, Tokenizer::decodePath, "a path <...>",
                              "a path <...>, a list of paths or None", "in the path list of ", what);
    }
    std::vector<std::string> parseStringList(const std::string& what) {
        return parseTokenList(TokenKind::String, Tokenizer::decodeString, "a quoted string",
                              "a quoted string or a list of strings", "in the list of ", what);
    }
    std::vector<Reference> parseReferences(const std::string& what);
    void parseLayerOffset(double& offset, double& scale, const std::string& what);
    std::map<double, Value> parseTimeSamples(const std::string& scalar, bool isArray, const std::string& what);

    // --- structure ---
    template <class Unclosed, class ReadEntry>
    void parseEntriesUntil(char close, const char* skipped, Unclosed&& unclosed, ReadEntry&& readEntry);
    template <class Handler>
    void parseMetadataList(const std::string& owner, Handler&& handle);
    void parseLayerMetadata();
    void handlePrimMetadata(PrimSpec& spec, const std::string& key, ListOpKind op, const std::string& owner);
    void handlePropertyMetadata(std::map<std::string, Value>& metadata, const std::string& key,
                                const std::string& owner);
    void parsePrim(PrimSpec& parent, const std::string& parentPath);
    void parsePrimBody(PrimSpec& spec, const std::string& path, const Token& open);
    void parseProperty(PrimSpec& spec, const std::string& primPath);
    // What may come before a property's type: a list op and 'custom',
    // 'uniform', 'varying' or 'config'.
    struct PropertyQualifiers {
        bool isCustom = false;
        bool isUniform = false;
        ListOpKind op = ListOpKind::Explicit;
    };
    bool parsePropertyQualifiers(PropertyQualifiers& qualifiers, const std::string& primPath);
    void parseReorderStatement(const std::string& primPath);
    struct AttributeType {
        std::string scalar;
        std::string typeName;  // with "[]" for an array
        bool isArray = false;
    };
    AttributeType parseAttributeType(const std::string& primPath);
    std::string parseAttributeName(const std::string& typeName);
    void parseAttributeField(AttributeSpec& attr, const std::string& name, const AttributeType& type, ListOpKind op,
                             const std::string& owner);
    void parseAttributeMetadata(AttributeSpec& attr, const std::string& owner);
    void parseRelationship(PrimSpec& spec, const std::string& primPath, const Token& first, ListOpKind op,
                           bool isCustom);
    void parseVariantSet(PrimSpec& spec, const std::string& primPath);
    static ListOpKind listOpOf(const Token& t, bool& isListOp);

    std::string_view text_;
    Tokenizer tok_;
    std::string directory_;
    std::unique_ptr<Layer> layer_;
    int depth_ = 0;
};

ListOpKind Parser::listOpOf(const Token& t, bool& isListOp) {
    isListOp = true;
    if (t.isIdentifier("prepend")) return ListOpKind::Prepend;
    if (t.isIdentifier("append")) return ListOpKind::Append;
    if (t.isIdentifier("add")) return ListOpKind::Add;
    if (t.isIdentifier("delete")) return ListOpKind::Delete;
    if (t.isIdentifier("reorder")) return ListOpKind::Reorder;
    isListOp = false;
    return ListOpKind::Explicit;
}

std::unique_ptr<Layer> Parser::run() {
    layer_ = std::make_unique<Layer>();
    layer_->identifier = tok_.identifier();
    layer_->directory = directory_;
    layer_->pseudoRoot.specifier = Specifier::Over;
    if (peek().is('(')) parseLayerMetadata();
    while (true) {
        const Token& t = peek();
        if (t.kind == TokenKind::End) break;
        if (t.isIdentifier("def") || t.isIdentifier("over") || t.isIdentifier("class")) {
            parsePrim(layer_->pseudoRoot, "/");
        } else if (t.isIdentifier("reorder")) {
            next();
            if (!peek().isIdentifier("rootPrims")) fail(peek(), "expected 'rootPrims' after 'reorder'" + found(peek()));
            next();
            expectPunct('=', "after 'reorder rootPrims'");
            parseStringList("'reorder rootPrims'");
        } else {
            fail(t, "expected 'def', 'over' or 'class' at the top level of the layer" + found(t));
        }
    }
    return std::move(layer_);
}

// ---------------------------------------------------------------- values

double Parser::number(const Token& t, const std::string& what, bool allowBool) {
    double value = 0.0;
    if (t.kind == TokenKind::Number) {
        if (!parseDoubleText(t.text, value)) fail(t, "bad number '" + std::string(t.text) + "' in " + what);
        return value;
    }
    if (t.kind == TokenKind::Identifier) {
        if (t.text == "inf" || t.text == "nan") {
            parseDoubleText(t.text, value);
            return value;
        }
        if (allowBool && (t.text == "true" || t.text == "false")) return t.text == "true" ? 1.0 : 0.0;
    }
    fail(t, "expected a number in " + what + found(t));
}

// Reads `count` items separated by ',' (readItem reads one); `nouns` names
// them in messages ("components", "rows").
template <class ReadItem>
void Parser::parseCounted(int count, const char* nouns, const std::string& scalar, const std::string& what,
                          ReadItem&& readItem) {
    for (int i = 0; i < count; ++i) {
        if (i > 0) {
            if (peek().is(')')) {
                fail(peek(), "expected " + std::to_string(count) + " " + nouns + " in a " + scalar + " value in " +
                                 what + ", found " + std::to_string(i));
            }
            expectPunct(',', std::string("between the ") + nouns + " of a " + scalar + " value in " + what);
        }
        readItem();
    }
}

// Reads "item, item, ..." (a trailing ',' allowed) and then `close`; the opening
// punctuation is already read. A missing separator fails with
// "expected ',' or '<close>' " + where + what.
template <class ReadItem>
void Parser::parseItemsUntil(char close, const char* where, const std::string& what, ReadItem&& readItem) {
    while (!peek().is(close)) {
        readItem();
        if (peek().is(',')) {
            next();
        } else if (!peek().is(close)) {
            fail(peek(), std::string("expected ',' or '") + close + "' " + where + what + found(peek()));
        }
    }
    next();
}

// The forms a list-op value takes: None (no items), one item alone, or
// [item, item, ...]. readItem(inList) reads one item and fails, with its own
// message, where there is none; `where` is as for parseItemsUntil.
template <class ReadItem>
void Parser::parseListOpItems(const char* where, const std::string& what, ReadItem&& readItem) {
    const Token t = peek();
    if (t.isIdentifier("None")) {
        next();
        return;
    }
    if (!t.is('[')) {
        readItem(false);
        return;
    }
    next();
    parseItemsUntil(']', where, what, [&] { readItem(true); });
}

void Parser::parseTuple(int count, const std::string& scalar, Value& out, const std::string& what) {
    Token open = peek();
    if (!open.is('(')) {
        fail(open, "expected '(' to start a " + scalar + " value (" + std::to_string(count) + " components) in " +
                       what + found(open));
    }
    next();
    parseCounted(count, "components", scalar, what, [&] { out.numbers.push_back(number(next(), what, false)); });
    if (peek().is(',')) next();  // trailing comma
    if (!peek().is(')')) {
        if (peek().kind == TokenKind::Number) {
            fail(peek(), "too many components in a " + scalar + " value in " + what + " (expected " +
                             std::to_string(count) + ")");
        }
        fail(peek(), "expected ')' to close a " + scalar + " value in " + what + found(peek()));
    }
    next();
}

void Parser::parseScalar(const std::string& scalar, Value& out, const std::string& what) {
    const Token& t = peek();
    if (scalar == "string" || scalar == "token") {
        if (t.kind != TokenKind::String) fail(t, "expected a quoted " + scalar + " in " + what + found(t));
        out.strings.push_back(Tokenizer::decodeString(next()));
        return;
    }
    if (scalar == "asset") {
        if (t.kind != TokenKind::Asset) fail(t, "expected an asset path @...@ in " + what + found(t));
        out.strings.push_back(Tokenizer::decodeAsset(next()));
        return;
    }
    if (scalar == "path") {
        if (t.kind != TokenKind::Path) fail(t, "expected a path <...> in " + what + found(t));
        out.strings.push_back(Tokenizer::decodePath(next()));
        return;
    }
    if (scalar == "dictionary") {
        Value dictionary = parseDictionary(what);
        out.keys = std::move(dictionary.keys);
        out.items = std::move(dictionary.items);
        return;
    }
    const int matrixDim = matrixDimensionOf(scalar);
    if (matrixDim > 0) {
        Token open = peek();
        if (!open.is('(')) fail(open, "expected '(' to start a " + scalar + " value in " + what + found(open));
        next();
        parseCounted(matrixDim, "rows", scalar, what, [&] { parseTuple(matrixDim, scalar + " row", out, what); });
        if (peek().is(',')) next();
        expectPunct(')', "to close a " + scalar + " value in " + what);
        return;
    }
    const int tuple = tupleSizeOf(scalar);
    if (tuple > 1) {
        parseTuple(tuple, scalar, out, what);
        return;
    }
    out.numbers.push_back(number(next(), what, scalar == "bool"));
}

Value Parser::parseTyped(const std::string& scalar, bool isArray, const std::string& what) {
    Value value;
    value.typeName = isArray ? scalar + "[]" : scalar;
    value.isArray = isArray;
    value.tupleSize = std::max(1, tupleSizeOf(scalar));
    const Token& first = peek();
    if (first.isIdentifier("None")) {
        next();
        value.isBlocked = true;
        return value;
    }
    if (!isArray) {
        parseScalar(scalar, value, what);
        return value;
    }
    DepthGuard guard(*this, first);
    Token open = peek();
    if (!open.is('[')) fail(open, "expected '[' to start the " + scalar + "[] value of " + what + found(open));
    next();
    parseItemsUntil(']', "in the array value of ", what, [&] {
        if (peek().kind == TokenKind::End) {
            fail(peek(), "expected ']' to close the array opened at " + at(open) + " in " + what + found(peek()));
        }
        parseScalar(scalar, value, what);
    });
    return value;
}

Value Parser::parseGeneric(const std::string& what) {
    const Token t = peek();
    DepthGuard guard(*this, t);
    Value value;
    switch (t.kind) {
        case TokenKind::String:
            value.typeName = "string";
            value.strings.push_back(Tokenizer::decodeString(next()));
            return value;
        case TokenKind::Number:
            value.typeName = "double";
            value.numbers.push_back(number(next(), what, false));
            return value;
        case TokenKind::Asset:
            value.typeName = "asset";
            value.strings.push_back(Tokenizer::decodeAsset(next()));
            return value;
        case TokenKind::Path:
            value.typeName = "path";
            value.strings.push_back(Tokenizer::decodePath(next()));
            return value;
        case TokenKind::Identifier:
            next();
            return identifierValue(t, what);
        case TokenKind::Punct:
            break;
        case TokenKind::End:
            fail(t, "expected a value for " + what + found(t));
    }
    if (t.is('{')) return parseDictionary(what);
    if (t.is('(')) return parseGenericTuple(what);
    if (t.is('[')) return parseGenericList(t, what);
    fail(t, "expected a value for " + what + found(t));
}

// An untyped identifier: a bool, None, inf or nan, or else a token.
Value Parser::identifierValue(const Token& t, const std::string& what) {
    Value value;
    if (t.text == "true" || t.text == "false") {
        value.typeName = "bool";
        value.numbers.push_back(t.text == "true" ? 1.0 : 0.0);
    } else if (t.text == "None") {
        value.isBlocked = true;
    } else if (t.text == "inf" || t.text == "nan") {
        value.typeName = "double";
        value.numbers.push_back(number(t, what, false));
    } else {
        value.typeName = "token";
        value.strings.emplace_back(t.text);
    }
    return value;
}

// An untyped tuple, nested tuples flattened into its numbers.
Value Parser::parseGenericTuple(const std::string& what) {
    Value value;
    next();
    value.typeName = "tuple";
    parseItemsUntil(')', "in a tuple in ", what, [&] {
        if (peek().is('(')) {
            Value inner = parseGeneric(what);
            value.numbers.insert(value.numbers.end(), inner.numbers.begin(), inner.numbers.end());
        } else {
            value.numbers.push_back(number(next(), what, false));
        }
    });
    value.tupleSize = std::max<int>(1, static_cast<int>(value.numbers.size()));
    return value;
}

Value Parser::parseGenericList(const Token& open, const std::string& what) {
    next();
    std::vector<Value> elements;
    parseItemsUntil(']', "in a list in ", what, [&] {
        if (peek().kind == TokenKind::End) {
            fail(peek(), "expected ']' to close the list opened at " + at(open) + " in " + what + found(peek()));
        }
        elements.push_back(parseGeneric(what));
    });
    return arrayOrList(std::move(elements));
}

Value Parser::arrayOrList(std::vector<Value> elements) {
    Value value;
    value.isArray = true;
    // A homogeneous list becomes an array of that type; anything else a "list".
    bool sameType = !elements.empty();
    for (const Value& e : elements) {
        if (e.typeName != elements.front().typeName || e.isBlocked || e.isDictionary() || e.isArray ||
            e.typeName == "list" || e.numbers.size() != elements.front().numbers.size()) {
            sameType = false;
        }
    }
    if (sameType) {
        const Value& first = elements.front();
        value.typeName = first.typeName + "[]";
        value.tupleSize = first.isStringType() ? 1 : std::max<int>(1, static_cast<int>(first.numbers.size()));
        for (Value& e : elements) {
            value.numbers.insert(value.numbers.end(), e.numbers.begin(), e.numbers.end());
            for (std::string& s : e.strings) value.strings.push_back(std::move(s));
        }
    } else {
        value.typeName = "list";
        value.items = std::move(elements);
    }
    return value;
}

Value Parser::parseDictionary(const std::string& what) {
    const Token open = peek();
    DepthGuard guard(*this, open);
    if (!open.is('{')) fail(open, "expected '{' to start a dictionary in " + what + found(open));
    next();
    Value dictionary;
    dictionary.typeName = "dictionary";
    auto set = [&dictionary](std::string key, Value v) {
        for (size_t i = 0; i < dictionary.keys.size(); ++i) {
            if (dictionary.keys[i] == key) {
                dictionary.items[i] = std::move(v);
                return;
            }
        }
        dictionary.keys.push_back(std::move(key));
        dictionary.items.push_back(std::move(v));
    };
    auto unclosed = [&] { return "the dictionary opened at " + at(open) + " in " + what; };
    parseEntriesUntil('}', ";,", unclosed, [&](const Token& t) {
        if (t.kind == TokenKind::Identifier) {
            // typed entry: type[] key = value
            next();
            std::string scalar(t.text);
            bool isArray = false;
            if (peek().is('[')) {
                next();
                expectPunct(']', "after '" + scalar + "[' in a dictionary in " + what);
                isArray = true;
            }
            if (scalar != "dictionary" && tupleSizeOf(scalar) == 0) {
                fail(t, "unknown value type '" + scalar + "' in a dictionary in " + what);
            }
            const Token keyToken = peek();
            std::string key;
            if (keyToken.kind == TokenKind::Identifier) {
                key = std::string(keyToken.text);
            } else if (keyToken.kind == TokenKind::String) {
                key = Tokenizer::decodeString(keyToken);
            } else {
                fail(keyToken, "expected a dictionary key after '" + scalar + (isArray ? "[]" : "") + "' in " +
                                   what + found(keyToken));
            }
            next();
            expectPunct('=', "after dictionary key '" + key + "' in " + what);
            Value v = (scalar == "dictionary" && !isArray) ? parseDictionary(what)
                                                            : parseTyped(scalar, isArray, "'" + key + "' in " + what);
            set(std::move(key), std::move(v));
            endStatement("dictionary entry '" + dictionary.keys.back() + "'");
            return;
        }
        if (t.kind == TokenKind::String || t.kind == TokenKind::Path) {
            // untyped entry: "key": value  (relocates, prefixSubstitutions, ...)
            next();
            std::string key = t.kind == TokenKind::String ? Tokenizer::decodeString(t) : Tokenizer::decodePath(t);
            expectPunct(':', "after the key " + Tokenizer::describe(t) + " in a dictionary in " + what);
            set(std::move(key), parseGeneric(what));
            return;
        }
        fail(t, "expected a dictionary entry ('type name = value') or '}' in " + what + found(t));
    });
    return dictionary;
}

Value Parser::parseMetadataValue(const std::string& key, const std::string& what) {
    std::string type = knownMetadataType(key);
    if (type.empty()) return parseGeneric(what);
    if (type == "dictionary") {
        if (peek().isIdentifier("None")) {
            next();
            Value blocked;
            blocked.typeName = "dictionary";
            blocked.isBlocked = true;
            return blocked;
        }
        return parseDictionary(what);
    }
    return parseTypedName(type, what);
}

// A list-op value of Path or String tokens. `item` and `itemOrList` name what
// was expected in messages; `where` is as for parseItemsUntil.
std::vector<std::string> Parser::parseTokenList(TokenKind kind, std::string (*decode)(const Token&), const char* item,
                                                const char* itemOrList, const char* where, const std::string& what) {
    std::vector<std::string> items;
    parseListOpItems(where, what, [&](bool inList) {
        const Token& t = peek();
        if (t.kind != kind) {
            fail(t, inList ? "expected " + std::string(item) + " or ']' in " + what + found(t)
                           : "expected " + std::string(itemOrList) + " for " + what + found(t));
        }
        items.push_back(decode(next()));
    });
    return items;
}

void Parser::parseLayerOffset(double& offset, double& scale, const std::string& what) {
    parseMetadataList(what, [&](const Token& key, ListOpKind) {
        if (key.text == "offset") {
            offset = number(next(), "the layer offset of " + what, false);
        } else if (key.text == "scale") {
            scale = number(next(), "the layer scale of " + what, false);
        } else {
            parseGeneric(what);  // customData and other reference metadata: parsed and ignored
        }
    });
}

std::vector<Reference> Parser::parseReferences(const std::string& what) {
    std::vector<Reference> references;
    parseListOpItems("in the list of ", what, [&](bool inList) {
        if (inList && peek().kind == TokenKind::End) {
            fail(peek(), "expected ']' to close the list of " + what + found(peek()));
        }
        const Token t = peek();
        Reference reference;
        reference.location = location(t);
        reference.baseDirectory = directory_;
        if (t.kind == TokenKind::Asset) {
            reference.assetPath = Tokenizer::decodeAsset(next());
            if (peek().kind == TokenKind::Path) reference.primPath = Tokenizer::decodePath(next());
        } else if (t.kind == TokenKind::Path) {
            reference.primPath = Tokenizer::decodePath(next());
        } else {
            fail(t, "expected an asset path @...@ or a prim path <...> in " + what + found(t));
        }
        if (reference.assetPath.empty() && reference.primPath.empty()) {
            fail(t, "empty reference in " + what + " (expected @file@, @file@</Prim> or </Prim>)");
        }
        if (peek().is('(')) parseLayerOffset(reference.offset, reference.scale, what);
        references.push_back(std::move(reference));
    });
    return references;
}

std::map<double, Value> Parser::parseTimeSamples(const std::string& scalar, bool isArray, const std::string& what) {
    std::map<double, Value> samples;
    const Token open = peek();
    if (!open.is('{')) fail(open, "expected '{' to start the timeSamples of " + what + found(open));
    next();
    auto unclosed = [&] { return "the timeSamples of " + what + " opened at " + at(open); };
    parseEntriesUntil('}', "", unclosed, [&](const Token& t) {
        if (t.kind != TokenKind::Number && !t.isIdentifier("inf") && !t.isIdentifier("nan")) {
            fail(t, "expected a time code (a number) or '}' in the timeSamples of " + what + found(t));
        }
        next();
        double time = number(t, "the timeSamples of " + what, false);
        if (std::isnan(time)) fail(t, "time code nan in the timeSamples of " + what);
        expectPunct(':', "after time code " + std::string(t.text) + " in the timeSamples of " + what);
        samples[time] = parseTyped(scalar, isArray, what + " at time " + std::string(t.text));
        if (peek().is(',')) {
            next();
        } else if (!peek().is('}')) {
            fail(peek(), "expected ',' or '}' after the sample at time " + std::string(t.text) + " of " + what +
                             found(peek()));
        }
    });
    return samples;
}

// ---------------------------------------------------------------- structure

// Reads entries up to `close`, then `close` itself: readEntry(t) reads the one
// that starts at t. Any of the `skipped` punctuation between entries is passed
// over; the end of the text fails with "expected '<close>' to close " + unclosed().
template <class Unclosed, class ReadEntry>
void Parser::parseEntriesUntil(char close, const char* skipped, Unclosed&& unclosed, ReadEntry&& readEntry) {
    while (true) {
        const Token t = peek();
        if (t.is(close)) {
            next();
            return;
        }
        bool skip = false;
        for (const char* c = skipped; *c; ++c) skip = skip || t.is(*c);
        if (skip) {
            next();
            continue;
        }
        if (t.kind == TokenKind::End) {
            fail(t, std::string("expected '") + close + "' to close " + unclosed() + found(t));
        }
        readEntry(t);
    }
}

template <class Handler>
void Parser::parseMetadataList(const std::string& owner, Handler&& handle) {
    const Token open = peek();
    DepthGuard guard(*this, open);
    next();  // '('
    auto unclosed = [&] { return "the metadata of " + owner + " opened at " + at(open); };
    parseEntriesUntil(')', ";", unclosed, [&](const Token& t) {
        if (t.kind == TokenKind::String) {
            handle(t, ListOpKind::Explicit);  // a bare string: the comment / doc
        } else {
            bool isListOp = false;
            ListOpKind op = listOpOf(t, isListOp);
            if (isListOp) next();
            const Token key = peek();
            if (key.kind != TokenKind::Identifier) {
                fail(key, "expected a metadata name or ')' in the metadata of " + owner + found(key));
            }
            next();
            expectPunct('=', "after metadata name '" + std::string(key.text) + "' of " + owner);
            handle(key, op);
        }
        const Token& after = peek();
        if (!(after.is(')') || after.is(';') || after.newlineBefore || after.kind == TokenKind::End)) {
            fail(after, "expected a new line, ';' or ')' after a metadata entry of " + owner + found(after));
        }
    });
}

void Parser::parseLayerMetadata() {
    LayerInfo& info = layer_->info;
    parseMetadataList("the layer", [&](const Token& key, ListOpKind) {
        if (key.kind == TokenKind::String) {
            next();
            std::string text = Tokenizer::decodeString(key);
            info.metadata["comment"] = stringValue(text);
            if (info.doc.empty()) info.doc = text;
            return;
        }
        const std::string name(key.text);
        const std::string what = "layer metadata '" + name + "'";
        if (name == "subLayers") {
            const Token open = peek();
            if (!open.is('[')) fail(open, "expected '[' to start the subLayers list" + found(open));
            next();
            Value list;
            list.typeName = "asset[]";
            list.isArray = true;
            parseItemsUntil(']', "in subLayers", std::string(), [&] {
                const Token item = peek();
                if (item.kind != TokenKind::Asset) fail(item, "expected an asset path @...@ or ']' in subLayers" + found(item));
                next();
                SubLayer sub;
                sub.assetPath = Tokenizer::decodeAsset(item);
                sub.location = location(item);
                if (peek().is('(')) parseLayerOffset(sub.offset, sub.scale, "sublayer " + Tokenizer::describe(item));
                info.subLayers.push_back(sub.assetPath);
                list.strings.push_back(sub.assetPath);
                layer_->subLayers.push_back(std::move(sub));
            });
            info.metadata[name] = std::move(list);
            return;
        }
        Value value = parseMetadataValue(name, what);
        if (name == "doc" || name == "documentation") info.doc = value.stringOr();
        if (name == "defaultPrim") info.defaultPrim = value.stringOr();
        if (name == "upAxis") info.upAxis = value.stringOr(info.upAxis);
        if (name == "metersPerUnit") info.metersPerUnit = value.numberOr(info.metersPerUnit);
        if (name == "startTimeCode") info.startTimeCode = value.numberOr();
        if (name == "endTimeCode") info.endTimeCode = value.numberOr();
        if (name == "timeCodesPerSecond") info.timeCodesPerSecond = value.numberOr(info.timeCodesPerSecond);
        if (name == "framesPerSecond") info.framesPerSecond = value.numberOr(info.framesPerSecond);
        info.metadata[name] = std::move(value);
    });
    // As UsdStage::GetTimeCodesPerSecond: an unauthored timeCodesPerSecond
    // falls back to an authored framesPerSecond.
    if (!info.metadata.count("timeCodesPerSecond") && info.metadata.count("framesPerSecond")) {
        info.timeCodesPerSecond = info.framesPerSecond;
    }
}

void Parser::handlePrimMetadata(PrimSpec& spec, const std::string& key, ListOpKind op, const std::string& owner) {
    const std::string what = "metadata '" + key + "' of " + owner;
    if (key == "references") {
        spec.references.set(op, parseReferences(what));
    } else if (key == "payload" || key == "payloads") {
        spec.payloads.set(op, parseReferences(what));
    } else if (key == "apiSchemas") {
        spec.apiSchemas.set(op, parseStringList(what));
    } else if (key == "variantSets") {
        spec.variantSetNames.set(op, parseStringList(what));
    } else if (key == "inherits" || key == "specializes") {
        Value v;
        v.typeName = "path[]";
        v.isArray = true;
        v.strings = parsePathList(what);
        spec.metadata[key] = std::move(v);
    } else {
        spec.metadata[key] = parseMetadataValue(key, what);
    }
}

void Parser::handlePropertyMetadata(std::map<std::string, Value>& metadata, const std::string& key,
                                    const std::string& owner) {
    metadata[key] = parseMetadataValue(key, "metadata '" + key + "' of " + owner);
}

void Parser::parsePrim(PrimSpec& parent, const std::string& parentPath) {
    const Token specToken = next();
    DepthGuard guard(*this, specToken);
    auto spec = std::make_unique<PrimSpec>();
    spec->specifier = specToken.text == "def" ? Specifier::Def
                      : specToken.text == "class" ? Specifier::Class : Specifier::Over;
    spec->location = location(specToken);
    std::string declared(specToken.text);
    if (peek().kind == TokenKind::Identifier) {
        spec->typeName = std::string(next().text);
        declared += " " + spec->typeName;
    }
    const Token nameToken = peek();
    if (nameToken.kind != TokenKind::String) {
        fail(nameToken, "expected a prim name in quotes after '" + declared + "'" + found(nameToken));
    }
    next();
    spec->name = Tokenizer::decodeString(nameToken);
    if (!isValidPrimName(spec->name)) {
        fail(nameToken, "invalid prim name \"" + spec->name + "\" (a prim name is a letter or '_' followed by "
                        "letters, digits or '_')");
    }
    const std::string path = (parentPath == "/" ? "/" : parentPath + "/") + spec->name;
    if (const PrimSpec* existing = parent.child(spec->name)) {
        fail(nameToken, "prim <" + path + "> is authored twice in this layer (first at " +
                            existing->location.toString() + ")");
    }
    const std::string owner = "prim <" + path + ">";
    if (peek().is('(')) {
        PrimSpec& target = *spec;
        parseMetadataList(owner, [&](const Token& key, ListOpKind op) {
            if (key.kind == TokenKind::String) {
                next();
                target.metadata["comment"] = stringValue(Tokenizer::decodeString(key));
                return;
            }
            handlePrimMetadata(target, std::string(key.text), op, owner);
        });
    }
    const Token open = peek();
    if (!open.is('{')) fail(open, "expected '{' to open the body of " + owner + found(open));
    next();
    PrimSpec* raw = spec.get();
    parent.childIndex[spec->name] = raw;
    parent.children.push_back(std::move(spec));
    parsePrimBody(*raw, path, open);
}

void Parser::parsePrimBody(PrimSpec& spec, const std::string& path, const Token& open) {
    auto unclosed = [&] { return "prim <" + path + "> opened at " + at(open); };
    parseEntriesUntil('}', ";", unclosed, [&](const Token& t) {
        if (t.kind != TokenKind::Identifier) {
            fail(t, "expected a property, a child prim or '}' in prim <" + path + ">" + found(t));
        }
        if (t.isIdentifier("def") || t.isIdentifier("over") || t.isIdentifier("class")) {
            parsePrim(spec, path);
        } else if (t.isIdentifier("variantSet")) {
            parseVariantSet(spec, path);
        } else {
            parseProperty(spec, path);
        }
    });
}

void Parser::parseProperty(PrimSpec& spec, const std::string& primPath) {
    const Token first = peek();
    PropertyQualifiers qualifiers;
    if (!parsePropertyQualifiers(qualifiers, primPath)) return;
    if (peek().isIdentifier("rel")) {
        parseRelationship(spec, primPath, first, qualifiers.op, qualifiers.isCustom);
        return;
    }
    const AttributeType type = parseAttributeType(primPath);
    const std::string name = parseAttributeName(type.typeName);
    const std::string owner = "attribute '" + name + "'";
    AttributeSpec& attr = spec.attributes[name];
    if (attr.name.empty()) {
        attr.name = name;
        attr.location = location(first);
    }
    attr.typeName = type.typeName;
    if (type.scalar == "asset") attr.assetDirectory = directory_;
    attr.isCustom = attr.isCustom || qualifiers.isCustom;
    attr.isUniform = attr.isUniform || qualifiers.isUniform;

    if (peek().is('.')) {
        parseAttributeField(attr, name, type, qualifiers.op, owner);
    } else if (peek().is('=')) {
        next();
        attr.defaultValue = parseTyped(type.scalar, type.isArray, owner);
    } else if (!peek().is('(') && !atStatementEnd()) {
        fail(peek(), "expected '=' or '(' after attribute name '" + name + "'" + found(peek()));
    }
    if (peek().is('(')) parseAttributeMetadata(attr, owner);
    endStatement(owner);
}

// Returns false when the statement was a whole 'reorder nameChildren' or
// 'reorder properties', not a property.
bool Parser::parsePropertyQualifiers(PropertyQualifiers& qualifiers, const std::string& primPath) {
    while (true) {
        const Token& t = peek();
        bool isListOp = false;
        ListOpKind kind = listOpOf(t, isListOp);
        if (isListOp) {
            qualifiers.op = kind;
            next();
            if (kind == ListOpKind::Reorder && (peek().isIdentifier("nameChildren") || peek().isIdentifier("properties"))) {
                parseReorderStatement(primPath);
                return false;
            }
        } else if (t.isIdentifier("custom")) {
            qualifiers.isCustom = true;
            next();
        } else if (t.isIdentifier("uniform")) {
            qualifiers.isUniform = true;
            next();
        } else if (t.isIdentifier("varying") || t.isIdentifier("config")) {
            next();
        } else {
            return true;
        }
    }
}

void Parser::parseReorderStatement(const std::string& primPath) {
    const Token what = next();
    expectPunct('=', "after 'reorder " + std::string(what.text) + "'");
    parseStringList("'reorder " + std::string(what.text) + "' in prim <" + primPath + ">");
    endStatement("'reorder " + std::string(what.text) + "'");
}

Parser::AttributeType Parser::parseAttributeType(const std::string& primPath) {
    const Token typeToken = peek();
    if (typeToken.kind != TokenKind::Identifier) {
        fail(typeToken, "expected an attribute type or 'rel' in prim <" + primPath + ">" + found(typeToken));
    }
    next();
    AttributeType type;
    type.typeName = std::string(typeToken.text);
    if (tupleSizeOf(type.typeName) == 0 || type.typeName == "path") {
        fail(typeToken, "unknown attribute type '" + type.typeName + "'");
    }
    type.scalar = type.typeName;
    if (peek().is('[')) {
        next();
        expectPunct(']', "after '" + type.scalar + "['");
        type.isArray = true;
        type.typeName += "[]";
    }
    return type;
}

std::string Parser::parseAttributeName(const std::string& typeName) {
    const Token nameToken = peek();
    if (nameToken.kind != TokenKind::Identifier) {
        fail(nameToken, "expected an attribute name after type '" + typeName + "'" + found(nameToken));
    }
    next();
    return std::string(nameToken.text);
}

// '<name>.timeSamples = ...' or '<name>.connect = ...'.
void Parser::parseAttributeField(AttributeSpec& attr, const std::string& name, const AttributeType& type,
                                 ListOpKind op, const std::string& owner) {
    next();
    const Token field = peek();
    if (field.isIdentifier("timeSamples")) {
        next();
        expectPunct('=', "after '" + name + ".timeSamples'");
        attr.timeSamples = parseTimeSamples(type.scalar, type.isArray, owner);
        attr.hasTimeSamples = true;
    } else if (field.isIdentifier("connect")) {
        next();
        expectPunct('=', "after '" + name + ".connect'");
        attr.connections.set(op, parsePathList("'" + name + ".connect'"));
    } else if (field.isIdentifier("spline")) {
        fail(field, "'" + name + ".spline': spline animation is not supported by the embedded reader");
    } else {
        fail(field, "expected 'timeSamples' or 'connect' after '" + name + ".'" + found(field));
    }
}

void Parser::parseAttributeMetadata(AttributeSpec& attr, const std::string& owner) {
    parseMetadataList(owner, [&](const Token& key, ListOpKind) {
        if (key.kind == TokenKind::String) {
            next();
            attr.metadata["comment"] = stringValue(Tokenizer::decodeString(key));
            return;
        }
        handlePropertyMetadata(attr.metadata, std::string(key.text), owner);
    });
}

void Parser::parseRelationship(PrimSpec& spec, const std::string& primPath, const Token& first, ListOpKind op,
                               bool isCustom) {
    next();  // rel
    const Token nameToken = peek();
    if (nameToken.kind != TokenKind::Identifier) {
        fail(nameToken, "expected a relationship name after 'rel' in prim <" + primPath + ">" + found(nameToken));
    }
    next();
    const std::string name(nameToken.text);
    const std::string owner = "relationship '" + name + "'";
    RelationshipSpec& rel = spec.relationships[name];
    if (rel.name.empty()) {
        rel.name = name;
        rel.location = location(first);
    }
    rel.isCustom = rel.isCustom || isCustom;
    if (peek().is('.')) {
        fail(peek(), "expected '=' or '(' after relationship name '" + name + "'" + found(peek()));
    }
    if (peek().is('=')) {
        next();
        rel.targets.set(op, parsePathList(owner));
    } else if (!peek().is('(') && !atStatementEnd()) {
        fail(peek(), "expected '=' or '(' after relationship name '" + name + "'" + found(peek()));
    }
    if (peek().is('(')) {
        parseMetadataList(owner, [&](const Token& key, ListOpKind) {
            if (key.kind == TokenKind::String) {
                next();
                return;
            }
            handlePropertyMetadata(rel.metadata, std::string(key.text), owner);
        });
    }
    endStatement(owner);
}

void Parser::parseVariantSet(PrimSpec& spec, const std::string& primPath) {
    const Token keyword = next();
    DepthGuard guard(*this, keyword);
    const Token nameToken = peek();
    if (nameToken.kind != TokenKind::String) {
        fail(nameToken, "expected the variant set name in quotes after 'variantSet'" + found(nameToken));
    }
    next();
    const std::string setName = Tokenizer::decodeString(nameToken);
    expectPunct('=', "after 'variantSet \"" + setName + "\"'");
    const Token open = peek();
    if (!open.is('{')) fail(open, "expected '{' to open variantSet \"" + setName + "\"" + found(open));
    next();
    VariantSetSpec* set = nullptr;
    for (VariantSetSpec& existing : spec.variantSets) {
        if (existing.name == setName) set = &existing;
    }
    if (!set) {
        spec.variantSets.emplace_back();
        set = &spec.variantSets.back();
        set->name = setName;
        set->location = location(keyword);
    }
    auto unclosed = [&] { return "variantSet \"" + setName + "\" opened at " + at(open); };
    parseEntriesUntil('}', "", unclosed, [&](const Token& t) {
        if (t.kind != TokenKind::String) {
            fail(t, "expected a variant name in quotes or '}' in variantSet \"" + setName + "\"" + found(t));
        }
        next();
        const std::string variantName = Tokenizer::decodeString(t);
        auto variant = std::make_unique<PrimSpec>();
        variant->name = variantName;
        variant->specifier = Specifier::Over;
        variant->location = location(t);
        const std::string path = primPath + "{" + setName + "=" + variantName + "}";
        if (peek().is('(')) {
            PrimSpec& target = *variant;
            parseMetadataList("variant " + path, [&](const Token& key, ListOpKind op) {
                if (key.kind == TokenKind::String) {
                    next();
                    return;
                }
                handlePrimMetadata(target, std::string(key.text), op, "variant " + path);
            });
        }
        const Token body = peek();
        if (!body.is('{')) fail(body, "expected '{' to open variant \"" + variantName + "\"" + found(body));
        next();
        PrimSpec* raw = variant.get();
        set->variants.emplace_back(variantName, std::move(variant));
        parsePrimBody(*raw, path, body);
    });
    endStatement("variantSet \"" + setName + "\"");
}

}  // namespace

std::unique_ptr<Layer> parseLayer(std::string_view text, const std::string& identifier,
                                  const std::string& directory) {
    checkHeader(text, identifier);
    Parser parser(text, identifier, directory);
    return parser.run();
}

}  // namespace hdhair::usda::detail
