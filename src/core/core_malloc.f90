!> The C library's allocation policy (core_malloc.c, which says why): during
!> the set-up, glibc's mmap threshold is pinned at its initial 128 kB, so
!> that the large temporaries a mesh reader frees do not raise it and leave
!> the partition and migration a fragmented heap; for the time loop it goes
!> to glibc's ceiling, so that the loop's temporaries are not mapped afresh
!> every cycle. A threshold set in the environment wins. No MPI here.
module core_malloc
  use, intrinsic :: iso_c_binding, only: c_int, c_long
  implicit none
  private
  public :: malloc_setup_policy, malloc_loop_policy

  !> Bytes: glibc's initial mmap threshold (mallopt(3)), for the set-up.
  integer, parameter :: SETUP_MMAP = 131072
  !> Bytes: glibc's ceiling for its adjusted mmap threshold on 64-bit
  !> systems (DEFAULT_MMAP_THRESHOLD_MAX, 4 MB x sizeof(long)), and the trim
  !> threshold the adjustment sets with it (twice), for the time loop.
  integer, parameter :: LOOP_MMAP = 33554432, LOOP_TRIM = 2 * LOOP_MMAP

  interface
    function c_malloc_setup(bytes) result(done) bind(c, name='impact3d_malloc_setup')
      import :: c_int, c_long
      integer(c_long), value :: bytes
      integer(c_int) :: done
    end function c_malloc_setup

    function c_malloc_loop(mmap_bytes, trim_bytes) result(done) &
        bind(c, name='impact3d_malloc_loop')
      import :: c_int, c_long
      integer(c_long), value :: mmap_bytes, trim_bytes
      integer(c_int) :: done
    end function c_malloc_loop
  end interface

contains

  !> The set-up's policy. state: 1 applied, 0 left to the environment's
  !> setting (MALLOC_MMAP_THRESHOLD_ or GLIBC_TUNABLES), -1 not available.
  subroutine malloc_setup_policy(state)
    integer, intent(out) :: state
    state = int(c_malloc_setup(int(SETUP_MMAP, c_long)))
  end subroutine malloc_setup_policy

  !> The time loop's policy, after malloc_setup_policy. state: 1 applied, 0
  !> nothing to undo (the set-up's policy was not applied), -1 refused.
  subroutine malloc_loop_policy(state)
    integer, intent(out) :: state
    state = int(c_malloc_loop(int(LOOP_MMAP, c_long), int(LOOP_TRIM, c_long)))
  end subroutine malloc_loop_policy

end module core_malloc
