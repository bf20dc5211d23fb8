!> The set-up's malloc policy (core_malloc): applied, then released for the
!> time loop, where the C library has mallopt; left alone, set-up and loop,
!> when the environment sets the mmap threshold (MALLOC_MMAP_THRESHOLD_, or
!> glibc.malloc.mmap_threshold in GLIBC_TUNABLES, which glibc itself
!> obeys; ctest runs this test without and with each).
!> Usage: test_core_malloc HAVE, HAVE = 1 if CMake found mallopt, else 0.
program test_core_malloc
  use core_malloc, only: malloc_setup_policy, malloc_loop_policy
  use check, only: check_true, check_summary
  implicit none
  character(len=8) :: have
  character(len=4096) :: value
  integer :: setup, loop, again, wanted, length, stat
  logical :: in_environment

  call get_command_argument(1, have)
  call get_environment_variable('MALLOC_MMAP_THRESHOLD_', value, length, stat)
  in_environment = stat == 0 .or. stat == -1
  call get_environment_variable('GLIBC_TUNABLES', value, length, stat)
  if (stat == 0) in_environment = in_environment .or. &
      index(value, 'glibc.malloc.mmap_threshold') > 0
  if (in_environment) then
    wanted = 0
  else if (trim(have) == '1') then
    wanted = 1
  else
    wanted = -1
  end if
  call malloc_setup_policy(setup)
  call check_true('set-up policy (1 applied, 0 environment, -1 no mallopt)', setup == wanted)
  call malloc_loop_policy(loop)
  ! Released only what the set-up applied (0: nothing to undo).
  call check_true('loop policy after the set-up''s', loop == merge(1, 0, wanted == 1))
  call malloc_loop_policy(again)
  call check_true('loop policy a second time: nothing to undo', again == 0)
  call check_summary()
end program test_core_malloc
