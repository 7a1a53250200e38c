// Subcommands of the proxygi program; each returns the process exit code.
#ifndef proxygiCommands_h
#define proxygiCommands_h

#include <string>
#include <vector>

namespace proxygi
{
namespace cli
{
using Args = std::vector<std::string>;

int RunSH(const Args& args);
int RunRender(const Args& args);
int RunReference(const Args& args);
int RunProxies(const Args& args);

/// Value of "--name value" (or default); sets `ok` false on a bad number.
std::string Option(const Args& args, const std::string& name, const std::string& fallback);
double NumberOption(const Args& args, const std::string& name, double fallback, bool& ok);
bool Flag(const Args& args, const std::string& name);
} // namespace cli
} // namespace proxygi

#endif
