#pragma once
// The .usda tokenizer: splits layer text into identifiers, numbers, strings,
// asset paths, prim paths and punctuation, tracking line and column (1-based,
// in bytes). Tokens are views into the text, so the text must outlive them;
// strings keep their quotes and are decoded on demand (decodeString).
// Internal to hdhair_usda.

#include <string>
#include <string_view>

namespace hdhair::usda::detail {

enum class TokenKind {
    End,         // end of the text
    Identifier,  // foo, primvars:displayColor, def, None, inf
    Number,      // 1, -2.5, 1e-05, -inf (validated by the parser)
    String,      // "a", 'a', """a""", '''a''' (text includes the quotes)
    Asset,       // @a.usda@ or @@@a@b.usda@@@ (text includes the @s)
    Path,        // </World/a.attr> (text includes the <>)
    Punct,       // ( ) [ ] { } = , ; : .
};

struct Token {
    TokenKind kind = TokenKind::End;
    std::string_view text;
    int line = 1;
    int column = 1;
    bool newlineBefore = false;  // a line break separates it from the previous token

    bool is(char punct) const { return kind == TokenKind::Punct && text.size() == 1 && text[0] == punct; }
    bool isIdentifier(std::string_view word) const { return kind == TokenKind::Identifier && text == word; }
};

class Tokenizer {
public:
    // `identifier` names the layer in error messages.
    Tokenizer(std::string_view text, std::string identifier);

    const Token& peek() const { return current_; }
    Token next();

    const std::string& identifier() const { return identifier_; }
    std::string location(const Token& token) const;           // "file:line:column"
    std::string location(int line, int column) const;
    // Throws hdhair::InputError "file:line:column: message".
    [[noreturn]] void fail(const Token& at, const std::string& message) const;
    [[noreturn]] void fail(int line, int column, const std::string& message) const;

    // "'['", "'points'", "string \"abc\"", "end of file", ...
    static std::string describe(const Token& token);
    // The contents of a String token with escapes resolved.
    static std::string decodeString(const Token& token);
    // The contents of an Asset token without the @s (@@@ escapes resolved).
    static std::string decodeAsset(const Token& token);
    // The contents of a Path token without the <>.
    static std::string decodePath(const Token& token);

private:
    Token scan();
    void skipSpaceAndComments(bool& sawNewline);
    int column() const { return static_cast<int>(pos_ - lineStart_) + 1; }
    void newline() { ++line_; lineStart_ = pos_; }

    std::string_view text_;
    std::string identifier_;
    size_t pos_ = 0;
    size_t lineStart_ = 0;
    int line_ = 1;
    Token current_;
};

}  // namespace hdhair::usda::detail
