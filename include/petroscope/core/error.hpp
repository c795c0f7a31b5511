#pragma once
// Errors that reach the user. Every message names what was wrong (file:line, option, value) and what
// was expected; the CLI prints it and exits non-zero.
#include <stdexcept>
#include <string>

namespace petroscope {

/// Bad input from a user: a file, an option, a value. The message is complete and located.
class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Bad input at a known place in a text file: the message reads "file:line: what".
InputError located_error(const std::string& file, int line, const std::string& what);

}  // namespace petroscope
