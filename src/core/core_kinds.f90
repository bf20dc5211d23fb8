!> Kind parameters for the whole code.
module core_kinds
  use, intrinsic :: iso_fortran_env, only: real64, int32, int64
  implicit none
  private
  public :: rk, ik, i8
  integer, parameter :: rk = real64 !< working real kind
  integer, parameter :: ik = int32 !< default integer kind
  integer, parameter :: i8 = int64 !< global ids and large counts
end module core_kinds
