#include "hdHair/usda/Tokenizer.h"

#include <cstdio>

#include "hdHair/base/InputError.h"

namespace hdhair::usda::detail {

namespace {

bool isIdentStart(unsigned char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c >= 0x80;
}
bool isIdentChar(unsigned char c) { return isIdentStart(c) || (c >= '0' && c <= '9'); }
bool isDigit(unsigned char c) { return c >= '0' && c <= '9'; }

std::string printable(std::string_view text, size_t limit = 40) {
    std::string out;
    for (char ch : text.substr(0, limit)) {
        unsigned char c = static_cast<unsigned char>(ch);
        if (c == '\n') {
            out += "\\n";
        } else if (c < 0x20 || c == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02x", c);
            out += buf;
        } else {
            out += ch;
        }
    }
    if (text.size() > limit) out += "...";
    return out;
}

}  // namespace

Tokenizer::Tokenizer(std::string_view text, std::string identifier)
    : text_(text), identifier_(std::move(identifier)) {
    // A UTF-8 byte order mark is not part of the layer.
    if (text_.size() >= 3 && text_.substr(0, 3) == "\xEF\xBB\xBF") {
        pos_ = 3;
        lineStart_ = 3;
    }
    current_ = scan();
}

Token Tokenizer::next() {
    Token token = current_;
    if (token.kind != TokenKind::End) current_ = scan();
    return token;
}

std::string Tokenizer::location(int line, int column) const {
    return identifier_ + ":" + std::to_string(line) + ":" + std::to_string(column);
}

std::string Tokenizer::location(const Token& token) const { return location(token.line, token.column); }

void Tokenizer::fail(const Token& at, const std::string& message) const { fail(at.line, at.column, message); }

void Tokenizer::fail(int line, int column, const std::string& message) const {
    throw InputError(location(line, column) + ": " + message);
}

void Tokenizer::skipSpaceAndComments(bool& sawNewline) {
    const size_t n = text_.size();
    while (pos_ < n) {
        char c = text_[pos_];
        if (c == '\n') {
            ++pos_;
            newline();
            sawNewline = true;
        } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            ++pos_;
        } else if (c == '#') {
            while (pos_ < n && text_[pos_] != '\n') ++pos_;
        } else if (c == '\\' && pos_ + 1 < n && (text_[pos_ + 1] == '\n' || text_[pos_ + 1] == '\r')) {
            // Line continuation: a backslash at the end of a line.
            ++pos_;
            if (text_[pos_] == '\r') ++pos_;
            if (pos_ < n && text_[pos_] == '\n') {
                ++pos_;
                newline();
            }
        } else {
            break;
        }
    }
}

Token Tokenizer::scan() {
    Token token;
    bool sawNewline = false;
    skipSpaceAndComments(sawNewline);
    token.newlineBefore = sawNewline;
    token.line = line_;
    token.column = column();
    const size_t n = text_.size();
    if (pos_ >= n) {
        token.kind = TokenKind::End;
        token.text = std::string_view();
        return token;
    }
    const size_t start = pos_;
    const unsigned char c = static_cast<unsigned char>(text_[pos_]);

    auto isNumberStart = [&](size_t at) {
        if (at >= n) return false;
        unsigned char d = static_cast<unsigned char>(text_[at]);
        if (isDigit(d)) return true;
        if (d == '.' && at + 1 < n && isDigit(static_cast<unsigned char>(text_[at + 1]))) return true;
        return false;
    };

    if (isNumberStart(pos_) || (c == '-' && (isNumberStart(pos_ + 1) ||
                                             (pos_ + 1 < n && isIdentStart(static_cast<unsigned char>(text_[pos_ + 1])))))) {
        // Numbers are scanned greedily (digits, letters, '.', and a sign after
        // an exponent) so that "1.2.3" or "12abc" is reported as one bad number.
        ++pos_;
        while (pos_ < n) {
            unsigned char d = static_cast<unsigned char>(text_[pos_]);
            if (isIdentChar(d) || d == '.') {
                ++pos_;
            } else if ((d == '+' || d == '-') && (text_[pos_ - 1] == 'e' || text_[pos_ - 1] == 'E')) {
                ++pos_;
            } else {
                break;
            }
        }
        token.kind = TokenKind::Number;
        token.text = text_.substr(start, pos_ - start);
        return token;
    }

    if (isIdentStart(c)) {
        ++pos_;
        while (true) {
            while (pos_ < n && isIdentChar(static_cast<unsigned char>(text_[pos_]))) ++pos_;
            // Namespaced names: primvars:displayColor, xformOp:rotateXYZ:tilt.
            if (pos_ + 1 < n && text_[pos_] == ':' && isIdentStart(static_cast<unsigned char>(text_[pos_ + 1]))) {
                ++pos_;
                continue;
            }
            break;
        }
        token.kind = TokenKind::Identifier;
        token.text = text_.substr(start, pos_ - start);
        return token;
    }

    if (c == '"' || c == '\'') {
        const char quote = static_cast<char>(c);
        const bool triple = pos_ + 2 < n && text_[pos_ + 1] == quote && text_[pos_ + 2] == quote;
        pos_ += triple ? 3 : 1;
        while (true) {
            if (pos_ >= n) fail(token, "unterminated string (end of file inside the string)");
            char d = text_[pos_];
            if (d == '\\') {
                if (pos_ + 1 >= n) fail(token, "unterminated string (end of file inside the string)");
                if (text_[pos_ + 1] == '\n') {
                    pos_ += 2;
                    newline();
                } else {
                    pos_ += 2;
                }
                continue;
            }
            if (d == '\n') {
                if (!triple) fail(token, "unterminated string (a line break inside a quoted string; use \"\"\" for multi-line text)");
                ++pos_;
                newline();
                continue;
            }
            if (d == quote) {
                if (!triple) {
                    ++pos_;
                    break;
                }
                if (pos_ + 2 < n && text_[pos_ + 1] == quote && text_[pos_ + 2] == quote) {
                    pos_ += 3;
                    break;
                }
            }
            ++pos_;
        }
        token.kind = TokenKind::String;
        token.text = text_.substr(start, pos_ - start);
        return token;
    }

    if (c == '@') {
        if (pos_ + 2 < n && text_[pos_ + 1] == '@' && text_[pos_ + 2] == '@') {
            pos_ += 3;
            while (true) {
                if (pos_ >= n || text_[pos_] == '\n') fail(token, "unterminated asset path (expected a closing '@@@')");
                if (text_[pos_] == '\\' && pos_ + 3 < n && text_.substr(pos_ + 1, 3) == "@@@") {
                    pos_ += 4;
                    continue;
                }
                if (pos_ + 2 < n && text_.substr(pos_, 3) == "@@@") {
                    pos_ += 3;
                    // "@@@a@@@@" : trailing @s belong to the path.
                    while (pos_ < n && text_[pos_] == '@') ++pos_;
                    break;
                }
                ++pos_;
            }
        } else {
            ++pos_;
            while (true) {
                if (pos_ >= n || text_[pos_] == '\n') fail(token, "unterminated asset path (expected a closing '@')");
                if (text_[pos_] == '@') {
                    ++pos_;
                    break;
                }
                ++pos_;
            }
        }
        token.kind = TokenKind::Asset;
        token.text = text_.substr(start, pos_ - start);
        return token;
    }

    if (c == '<') {
        ++pos_;
        while (true) {
            if (pos_ >= n || text_[pos_] == '\n') fail(token, "unterminated path (expected a closing '>')");
            if (text_[pos_] == '>') {
                ++pos_;
                break;
            }
            ++pos_;
        }
        token.kind = TokenKind::Path;
        token.text = text_.substr(start, pos_ - start);
        return token;
    }

    switch (c) {
        case '(': case ')': case '[': case ']': case '{': case '}':
        case '=': case ',': case ';': case ':': case '.':
            ++pos_;
            token.kind = TokenKind::Punct;
            token.text = text_.substr(start, 1);
            return token;
        default:
            break;
    }
    if (c >= 0x20 && c < 0x7f) {
        fail(token, std::string("unexpected character '") + static_cast<char>(c) + "'");
    }
    char buf[48];
    std::snprintf(buf, sizeof buf, "unexpected byte 0x%02x", c);
    fail(token, buf);
}

std::string Tokenizer::describe(const Token& token) {
    switch (token.kind) {
        case TokenKind::End:
            return "end of file";
        case TokenKind::String:
            return "string " + printable(token.text);
        case TokenKind::Asset:
            return "asset path " + printable(token.text);
        case TokenKind::Path:
            return "path " + printable(token.text);
        case TokenKind::Identifier:
        case TokenKind::Number:
        case TokenKind::Punct:
            break;
    }
    return "'" + printable(token.text) + "'";
}

std::string Tokenizer::decodeString(const Token& token) {
    std::string_view raw = token.text;
    size_t quoteLength = 1;
    if (raw.size() >= 6 && (raw.substr(0, 3) == "\"\"\"" || raw.substr(0, 3) == "'''")) quoteLength = 3;
    if (raw.size() < 2 * quoteLength) return std::string();
    std::string_view body = raw.substr(quoteLength, raw.size() - 2 * quoteLength);
    std::string out;
    out.reserve(body.size());
    for (size_t i = 0; i < body.size(); ++i) {
        char ch = body[i];
        if (ch != '\\' || i + 1 >= body.size()) {
            out += ch;
            continue;
        }
        char e = body[++i];
        switch (e) {
            case 'n': out += '\n'; break;
            case 't': out += '\t'; break;
            case 'r': out += '\r'; break;
            case 'a': out += '\a'; break;
            case 'b': out += '\b'; break;
            case 'f': out += '\f'; break;
            case 'v': out += '\v'; break;
            case '\n': break;  // escaped line break: a continuation
            case 'x': {
                int value = 0;
                int digits = 0;
                while (digits < 2 && i + 1 < body.size()) {
                    char h = body[i + 1];
                    int v = (h >= '0' && h <= '9') ? h - '0'
                            : (h >= 'a' && h <= 'f') ? h - 'a' + 10
                            : (h >= 'A' && h <= 'F') ? h - 'A' + 10 : -1;
                    if (v < 0) break;
                    value = value * 16 + v;
                    ++digits;
                    ++i;
                }
                if (digits == 0) {
                    out += 'x';
                } else {
                    out += static_cast<char>(value);
                }
                break;
            }
            default:
                if (e >= '0' && e <= '7') {
                    int value = e - '0';
                    int digits = 1;
                    while (digits < 3 && i + 1 < body.size() && body[i + 1] >= '0' && body[i + 1] <= '7') {
                        value = value * 8 + (body[++i] - '0');
                        ++digits;
                    }
                    out += static_cast<char>(value & 0xff);
                } else {
                    out += e;  // \\ \" \' and any other character stand for themselves
                }
                break;
        }
    }
    return out;
}

std::string Tokenizer::decodeAsset(const Token& token) {
    std::string_view raw = token.text;
    if (raw.size() >= 6 && raw.substr(0, 3) == "@@@") {
        std::string_view body = raw.substr(3, raw.size() - 6);
        std::string out;
        for (size_t i = 0; i < body.size(); ++i) {
            if (body[i] == '\\' && body.substr(i + 1, 3) == "@@@") {
                out += "@@@";
                i += 3;
            } else {
                out += body[i];
            }
        }
        return out;
    }
    if (raw.size() < 2) return std::string();
    return std::string(raw.substr(1, raw.size() - 2));
}

std::string Tokenizer::decodePath(const Token& token) {
    if (token.text.size() < 2) return std::string();
    return std::string(token.text.substr(1, token.text.size() - 2));
}

}  // namespace hdhair::usda::detail
