!> The run's status line on standard output (rank 0) and its text helpers.
module io_output
  use, intrinsic :: iso_fortran_env, only: output_unit
  use core_kinds, only: rk
  use core_timer, only: wall_time
  use mesh_local, only: mesh_t
  use hydro_state, only: state_t
  use hydro_driver, only: hydro_energies
  use solver_control, only: control_t
  use solver_eta, only: eta_t
  use parallel_env, only: par_rank, par_sum_array
  use io_deck, only: config_t
  use io_history, only: relative_error
  implicit none
  private
  public :: status_line, seconds

contains

  !> Seconds as text with two decimals, no leading blanks ('0.13', '3600.00').
  function seconds(value) result(text)
    real(rk), intent(in) :: value
    character(len=:), allocatable :: text
    character(len=24) :: buffer
    write(buffer, '(f24.2)') value
    text = trim(adjustl(buffer))
  end function seconds

  !> One status line: cycle, time, step and its limiter, energy error, speed,
  !> then progress: percent of t_end, wall time since the start (or restart)
  !> and the time left at the recent rate (eta_t).
  subroutine status_line(config, mesh, state, ctl, reason, rate, wall_start, eta)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(control_t), intent(in) :: ctl
    character(len=*), intent(in) :: reason
    real(rk), intent(in) :: rate, wall_start
    type(eta_t), intent(in) :: eta
    real(rk) :: sums(5), left
    character(len=:), allocatable :: eta_text
    call hydro_energies(mesh, state, sums)
    call par_sum_array(sums)
    if (par_rank() /= 0) return
    left = eta%seconds_left(config%t_end)
    eta_text = '?'
    if (left >= 0.0_rk) eta_text = seconds(left)//' s'
    write(output_unit, '(a,i8,a,es11.4,a,es10.3,a,a,a,i0,a,es9.2,a,es9.2,a,f5.1,a)') &
        'cycle', state%cycle, '  t=', state%time, '  dt=', state%dt, ' (', reason, ' zone ', &
        ctl%dt_zone, ')  dE/E=', relative_error(sums(1) + sums(2), state), &
        '  ', rate, ' zone-cycles/s  ', min(100.0_rk, 100.0_rk * state%time / config%t_end), &
        '% done  elapsed '//seconds(wall_time() - wall_start)//' s  ETA '//eta_text
    flush(output_unit)
  end subroutine status_line

end module io_output
