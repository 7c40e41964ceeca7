#pragma once
// Names of Ipopt's application return codes, for error messages.
#include <IpReturnCodes.hpp>

namespace cnclab {

const char* ipopt_status_name(Ipopt::ApplicationReturnStatus status);

}  // namespace cnclab
