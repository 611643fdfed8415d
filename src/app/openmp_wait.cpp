#include "avalanche/app/openmp_wait.hpp"

#include <cstdlib>
#include <sstream>

namespace avalanche {

OpenmpWait choose_openmp_wait(const std::string& loadavg) {
    const OpenmpWait sleep{"OMP_WAIT_POLICY", "passive"};
    std::istringstream in(loadavg);
    double one = 0.0, five = 0.0, fifteen = 0.0;
    long runnable = 0, total = 0;
    char slash = 0;
    if (!(in >> one >> five >> fifteen >> runnable >> slash >> total) || slash != '/' || runnable < 1)
        return sleep;
    return runnable == 1 ? OpenmpWait{"GOMP_SPINCOUNT", "3000"} : sleep;
}

std::string openmp_wait_in_effect() {
    if (const char* policy = std::getenv("OMP_WAIT_POLICY")) {
        const std::string p = policy;
        if (p == "passive" || p == "PASSIVE") return "passive";
        if (p == "active" || p == "ACTIVE") return "active";
    }
    if (const char* spins = std::getenv("GOMP_SPINCOUNT")) return std::string("spin ") + spins;
    return "default";
}

}  // namespace avalanche
