// Subcommands of the proxygi program; each returns the process exit code.
#ifndef proxygiCommands_h
#define proxygiCommands_h

#include <string>
#include <vector>

namespace proxygi
{
struct LoadedScene;
struct SceneDescription;
namespace budget
{
struct SceneFeatures;
}
namespace cli
{
using Args = std::vector<std::string>;

int RunSH(const Args& args);
int RunRender(const Args& args);
/// The analytic scene (sphere over plane against its closed form).
int RunRenderAnalytic(const Args& args);
/// A scene file (or the default bunny scene) through the GI filter.
int RunRenderScene(const Args& args, const std::string& scenePath);
int RunReference(const Args& args);
int RunProxies(const Args& args);
/// The CPU GI filter on a receiver mesh and a proxies file.
int RunShade(const Args& args);
/// An interactive window on a scene with GI live.
int RunView(const Args& args);
/// A scene's light cloud and a user light moving along a path through it.
int RunCloud(const Args& args);
/// The accuracy budget's model measured and fitted on this machine.
int RunCalibrate(const Args& args);
/// What the budget model predicts from, for a loaded scene (render and
/// calibrate): every object's points, the meshes, the light's terms.
bool SceneBudgetFeatures(const SceneDescription& scene, const LoadedScene& loaded,
  budget::SceneFeatures& features, std::string& error);

/// Value of the last "--name value" (or default); sets `ok` false on a bad number.
std::string Option(const Args& args, const std::string& name, const std::string& fallback);
double NumberOption(const Args& args, const std::string& name, double fallback, bool& ok);
bool Flag(const Args& args, const std::string& name);
/// The first argument that is neither an option, an option's value, nor one
/// of the value-less `flags`.
std::string Positional(const Args& args, const std::vector<std::string>& flags);
/// False, with an error naming it, if an argument starting with '-' is
/// neither one of `valued` (then followed by its value) nor of `flags`:
/// a misspelt or unsupported option is refused, not dropped.
bool KnownOptions(const Args& args, const char* command, const std::vector<std::string>& valued,
  const std::vector<std::string>& flags);
} // namespace cli
} // namespace proxygi

#endif
