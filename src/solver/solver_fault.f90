!> Testing aids of the failure path (&control fault_cycle, fault_kind): a
!> NaN energy or a zone turned inside out, injected on purpose.
module solver_fault
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use core_kinds, only: rk
  use mesh_local, only: mesh_t
  use mesh_geometry, only: hex_centroid
  use hydro_state, only: state_t
  implicit none
  private
  public :: inject_nan, inject_tangle

contains

  !> Testing aid (&control fault_nan_cycle): a NaN energy in global zone 1.
  subroutine inject_nan(mesh, state)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(inout) :: state
    integer :: z
    do z = 1, mesh%nzone
      if (mesh%zone_gid(z) == 1) state%zone_energy(z) = ieee_value(1.0_rk, ieee_quiet_nan)
    end do
  end subroutine inject_nan

  !> Testing aid (&control fault_kind = 'tangle'): turn global zone 1 inside
  !> out by mirroring its nodes through its centroid along x.
  subroutine inject_tangle(mesh, state)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(inout) :: state
    integer :: z, k, n
    real(rk) :: c(3)
    logical :: moved(mesh%nnode)
    moved = .false.
    do z = 1, mesh%nzone
      if (mesh%zone_gid(z) /= 1) cycle
      c = hex_centroid(state%node_position(:, mesh%zone_node(:, z)))
      do k = 1, 8
        n = mesh%zone_node(k, z)
        if (moved(n)) cycle
        state%node_position(1, n) = 2.0_rk * c(1) - state%node_position(1, n)
        moved(n) = .true.
      end do
    end do
  end subroutine inject_tangle

end module solver_fault
