// A broken mutant: the Lambert of ../lambert_emission_only.cpp without the contract
// header, as it once was. It does not compile, and check_mutants.sh must say so instead
// of counting its zero as the expected verdict.
namespace raylab::student {
Vec3 lambert(const Vec3&, const Vec3& Le, const Vec3&, const std::vector<LightSample>&) {
    return Le;
}
}  // namespace raylab::student
