!> What a restart checks: its deck against the deck stored in the dump (the
!> dumps store it with the version and the command line, io_output).
module app_provenance
  use, intrinsic :: iso_fortran_env, only: error_unit
  use core_status, only: status_t
  use io_deck, only: config_t, deck_restart_check
  use io_dump, only: dump_read_deck, DECK_TEXT_MAX
  use parallel_env, only: par_rank
  implicit none
  private
  public :: restart_deck_check

contains

  !> A restart's deck against the deck stored in the dump (before anything
  !> else is set up): a change outside &control and &output is an input
  !> error, or with force a warning.
  subroutine restart_deck_check(restart, config, force, status)
    character(len=*), intent(in) :: restart
    type(config_t), intent(in) :: config
    logical, intent(in) :: force
    type(status_t), intent(inout) :: status
    type(status_t) :: changes
    character(len=:), allocatable :: stored
    logical :: found
    integer :: i
    call dump_read_deck(restart, stored, found, status)
    if (.not. status%ok()) return
    if (.not. found) then
      if (par_rank() == 0) write(error_unit, '(a)') 'impact3d: warning: '''//trim(restart)// &
          ''' holds no deck (an older dump): the deck is not compared with it'
      return
    end if
    if (len(stored) >= DECK_TEXT_MAX) then
      if (par_rank() == 0) write(error_unit, '(a,i0,a)') 'impact3d: warning: the deck '// &
          'stored in '''//trim(restart)//''' was cut at ', DECK_TEXT_MAX, &
          ' characters: the deck is not compared with it'
      return
    end if
    call deck_restart_check(stored, config%deck_text, changes)
    if (changes%ok()) return
    if (force) then
      if (par_rank() == 0) then
        do i = 1, min(changes%count, size(changes%messages))
          write(error_unit, '(a)') 'impact3d: warning: '//trim(changes%messages(i))
        end do
        write(error_unit, '(a)') 'impact3d: warning: restarting with a changed deck '// &
            '(--restart-force)'
      end if
      return
    end if
    do i = 1, min(changes%count, size(changes%messages))
      call status%add(trim(changes%messages(i)))
    end do
    call status%add('restart: the deck differs from the one '''//trim(restart)// &
        ''' was written with outside &control and &output; restore it, or give '// &
        '--restart-force to restart anyway')
  end subroutine restart_deck_check

end module app_provenance
