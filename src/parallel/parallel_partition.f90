!> Zone partition by METIS (dual graph, face neighbours), computed on rank 0
!> and broadcast so that every rank holds the same owner array.
module parallel_partition
  use, intrinsic :: iso_c_binding, only: c_int32_t, c_float, c_ptr, c_null_ptr
  use core_kinds, only: ik
  use parallel_env, only: par_rank, par_bcast, par_abort
  implicit none
  private
  public :: partition_zones

  integer, parameter :: METIS_NOPTIONS = 40
  integer(c_int32_t), parameter :: METIS_OK = 1

  interface
    function metis_set_default_options(options) bind(c, name='METIS_SetDefaultOptions') &
        result(code)
      import :: c_int32_t
      integer(c_int32_t), intent(inout) :: options(*)
      integer(c_int32_t) :: code
    end function metis_set_default_options

    function metis_part_mesh_dual(ne, nn, eptr, eind, vwgt, vsize, ncommon, nparts, tpwgts, &
        options, objval, epart, npart) bind(c, name='METIS_PartMeshDual') result(code)
      import :: c_int32_t, c_ptr
      integer(c_int32_t), intent(in) :: ne, nn, ncommon, nparts
      integer(c_int32_t), intent(in) :: eptr(*), eind(*)
      type(c_ptr), value :: vwgt, vsize, tpwgts
      integer(c_int32_t), intent(in) :: options(*)
      integer(c_int32_t), intent(out) :: objval
      integer(c_int32_t), intent(out) :: epart(*), npart(*)
      integer(c_int32_t) :: code
    end function metis_part_mesh_dual
  end interface

contains

  !> part(z) in 0..nparts-1 for every zone of the global mesh.
  subroutine partition_zones(nnode, connectivity, nparts, part)
    integer, intent(in) :: nnode !< global nodes
    integer(ik), intent(in) :: connectivity(:, :) !< (8, nzone), 1-based global node ids
    integer, intent(in) :: nparts !< number of parts (ranks)
    integer(ik), intent(out) :: part(:) !< owner rank of each zone
    integer(c_int32_t), allocatable :: eptr(:), eind(:), epart(:), npart(:)
    integer(c_int32_t) :: options(METIS_NOPTIONS), objval, code
    integer :: nzone, z

    nzone = size(connectivity, 2)
    if (nparts == 1) then
      part = 0
      return
    end if
    if (par_rank() == 0) then
      allocate(eptr(nzone + 1), eind(8 * nzone), epart(nzone), npart(nnode))
      do z = 1, nzone + 1
        eptr(z) = int(8 * (z - 1), c_int32_t)
      end do
      eind = int(reshape(connectivity, [8 * nzone]) - 1, c_int32_t)
      code = metis_set_default_options(options)
      code = metis_part_mesh_dual(int(nzone, c_int32_t), int(nnode, c_int32_t), eptr, eind, &
          c_null_ptr, c_null_ptr, 4_c_int32_t, int(nparts, c_int32_t), c_null_ptr, options, &
          objval, epart, npart)
      if (code /= METIS_OK) call par_abort('METIS_PartMeshDual failed', 3)
      part = int(epart, ik)
    end if
    call par_bcast(part)
  end subroutine partition_zones

end module parallel_partition
