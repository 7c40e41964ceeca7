#pragma once
// Fills the registries of the lower modules (job kinds, paper tables) with
// cnclab's built-in studies. main() calls it first.
namespace cnclab {
void register_builtins();
}  // namespace cnclab
