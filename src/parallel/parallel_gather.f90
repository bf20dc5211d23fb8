!> Replicated gathers: every rank obtains the values of the same list of
!> global items. Each item is owned by exactly one rank, the others contribute
!> exact zeros, so the summed result is bitwise the owner's value on every
!> rank. Contact itself no longer replicates (it runs on RCB parts,
!> contact_parts); the unit test test_contact_parallel uses this gather.
module parallel_gather
  use mpi_f08
  use core_kinds, only: rk, i8
  use parallel_env, only: par_comm
  implicit none
  private
  public :: gather_by_id

contains

  !> values(:, i) = the owner's value of global item ids(i), on every rank.
  !> ids must be the same sorted list on every rank; owned_ids (sorted) and
  !> owned_values are this rank's items.
  subroutine gather_by_id(ids, owned_ids, owned_values, values)
    integer(i8), intent(in) :: ids(:) !< wanted global ids, sorted, same on all ranks
    integer(i8), intent(in) :: owned_ids(:) !< this rank's owned ids, sorted
    real(rk), intent(in) :: owned_values(:, :) !< (ncomp, nowned)
    real(rk), intent(out) :: values(:, :) !< (ncomp, size(ids))
    integer :: i, j
    values = 0.0_rk
    ! Merge the two sorted lists.
    i = 1
    j = 1
    do while (i <= size(ids) .and. j <= size(owned_ids))
      if (ids(i) == owned_ids(j)) then
        values(:, i) = owned_values(:, j)
        i = i + 1
        j = j + 1
      else if (ids(i) < owned_ids(j)) then
        i = i + 1
      else
        j = j + 1
      end if
    end do
    call MPI_Allreduce(MPI_IN_PLACE, values, size(values), MPI_DOUBLE_PRECISION, MPI_SUM, &
        par_comm())
  end subroutine gather_by_id

end module parallel_gather
