#include "cnclab/motion/ipopt_status.hpp"

#include "cnclab/core/enum_names.hpp"

namespace cnclab {
namespace {

// Ipopt's ApplicationReturnStatus names (IpReturnCodes_inc.h).
constexpr EnumName<Ipopt::ApplicationReturnStatus> kIpoptStatusNames[] = {
    {Ipopt::Solve_Succeeded, "Solve_Succeeded"},
    {Ipopt::Solved_To_Acceptable_Level, "Solved_To_Acceptable_Level"},
    {Ipopt::Infeasible_Problem_Detected, "Infeasible_Problem_Detected"},
    {Ipopt::Search_Direction_Becomes_Too_Small, "Search_Direction_Becomes_Too_Small"},
    {Ipopt::Diverging_Iterates, "Diverging_Iterates"},
    {Ipopt::User_Requested_Stop, "User_Requested_Stop"},
    {Ipopt::Feasible_Point_Found, "Feasible_Point_Found"},
    {Ipopt::Maximum_Iterations_Exceeded, "Maximum_Iterations_Exceeded"},
    {Ipopt::Restoration_Failed, "Restoration_Failed"},
    {Ipopt::Error_In_Step_Computation, "Error_In_Step_Computation"},
    {Ipopt::Maximum_CpuTime_Exceeded, "Maximum_CpuTime_Exceeded"},
    {Ipopt::Not_Enough_Degrees_Of_Freedom, "Not_Enough_Degrees_Of_Freedom"},
    {Ipopt::Invalid_Problem_Definition, "Invalid_Problem_Definition"},
    {Ipopt::Invalid_Option, "Invalid_Option"},
    {Ipopt::Invalid_Number_Detected, "Invalid_Number_Detected"},
    {Ipopt::Unrecoverable_Exception, "Unrecoverable_Exception"},
    {Ipopt::NonIpopt_Exception_Thrown, "NonIpopt_Exception_Thrown"},
    {Ipopt::Insufficient_Memory, "Insufficient_Memory"},
    {Ipopt::Internal_Error, "Internal_Error"}};

}  // namespace

const char* ipopt_status_name(Ipopt::ApplicationReturnStatus s) {
  return enum_name(kIpoptStatusNames, s, "unknown status");
}

}  // namespace cnclab
