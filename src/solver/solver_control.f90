!> The per-cycle control reduction: every rank's stable step (and the zone
!> that sets it), its first failure (zero or negative volume, NaN) and its
!> clean-stop request, gathered in one typed record so that every rank learns
!> the global step (ties to the lowest zone id), the first failure and the
!> strongest stop request.
module solver_control
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use core_kinds, only: rk, i8
  use mesh_local, only: mesh_t
  use mesh_geometry, only: hex_centroid
  use hydro_state, only: state_t, hydro_options_t
  use hydro_kernels, only: DT_CFL
  use hydro_driver, only: hydro_time_step
  use core_signal, only: signal_caught
  use parallel_env, only: par_rank, par_size, par_allgather
  use solver_schedule, only: schedule_t
  implicit none
  private
  public :: control_reduce, control_stop_request, control_step_failed

  !> Failure kinds.
  integer, parameter, public :: FAIL_NONE = 0, FAIL_VOLUME = 1, FAIL_NAN = 2, FAIL_DT = 3
  !> Clean-stop requests; the largest over the ranks wins.
  integer, parameter, public :: STOP_NONE = 0, STOP_FILE = 1, STOP_WALL = 2, STOP_SIGNAL = 3

  !> What the end-of-cycle reduction found.
  type, public :: control_t
    real(rk) :: dt = huge(1.0_rk) !< stable step
    integer(i8) :: dt_zone = 0 !< global id of the zone that sets it
    real(rk) :: dt_position(3) = 0.0_rk !< and its centroid
    integer :: dt_reason = DT_CFL
    integer :: fail = FAIL_NONE
    integer(i8) :: fail_id = 0 !< global id of the failed zone, or minus a node's
    real(rk) :: fail_position(3) = 0.0_rk
    integer :: stop = STOP_NONE !< a clean stop requested (STOP file, wall-time limit, signal)
    integer :: stop_signal = 0 !< with STOP_SIGNAL: the signal (largest number over the ranks)
  end type control_t

  !> One rank's contribution.
  type :: record_t
    real(rk) :: dt = huge(1.0_rk)
    real(rk) :: dt_position(3) = 0.0_rk
    real(rk) :: fail_position(3) = 0.0_rk
    integer(i8) :: dt_zone = 0
    integer(i8) :: dt_reason = DT_CFL
    integer(i8) :: fail = FAIL_NONE
    integer(i8) :: fail_id = 0
    integer(i8) :: stop = STOP_NONE
    integer(i8) :: stop_signal = 0
  end type record_t

contains

  !> Local checks, local stable step, one gather: the control of the cycle.
  subroutine control_reduce(mesh, state, opt, bad, bad_kind, ctl, stop_request, stop_signal)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(hydro_options_t), intent(in) :: opt
    integer, intent(in) :: bad !< local zone with bad volume (0 = none) from the last update
    integer, intent(in) :: bad_kind !< FAIL_VOLUME from an earlier stage, else FAIL_NONE
    type(control_t), intent(out) :: ctl
    integer, intent(in), optional :: stop_request !< this rank's STOP_* request
    integer, intent(in), optional :: stop_signal !< with STOP_SIGNAL: the signal this rank caught
    type(record_t) :: mine
    real(rk), allocatable :: reals(:, :)
    integer(i8), allocatable :: ints(:, :)
    integer :: zone, reason, z, n, r

    call hydro_time_step(mesh, state, opt, mine%dt, zone, reason)
    mine%dt_reason = reason
    if (bad > 0 .or. bad_kind /= FAIL_NONE) then
      mine%fail = FAIL_VOLUME
      z = max(bad, 1)
      mine%fail_id = mesh%zone_gid(z)
      ! Where the zone was at the start of the cycle (its new corners may be garbage).
      mine%fail_position = hex_centroid(state%node_position_old(:, mesh%zone_node(:, z)))
    else
      do z = 1, mesh%nzone_owned
        if (ieee_is_nan(state%zone_energy(z))) then
          mine%fail = FAIL_NAN
          mine%fail_id = mesh%zone_gid(z)
          mine%fail_position = hex_centroid(state%node_position(:, mesh%zone_node(:, z)))
          exit
        end if
      end do
      if (mine%fail == FAIL_NONE) then
        do n = 1, mesh%nnode_owned
          if (any(ieee_is_nan(state%node_velocity(:, n)))) then
            mine%fail = FAIL_NAN
            mine%fail_id = -mesh%node_gid(n)
            mine%fail_position = state%node_position(:, n)
            exit
          end if
        end do
      end if
    end if
    if (present(stop_request)) mine%stop = stop_request
    if (present(stop_signal)) mine%stop_signal = stop_signal
    if (zone > 0) then
      mine%dt_zone = mesh%zone_gid(zone)
      mine%dt_position = hex_centroid(state%node_position(:, mesh%zone_node(:, zone)))
    end if
    allocate(reals(7, par_size()), ints(6, par_size()))
    call par_allgather([mine%dt, mine%dt_position, mine%fail_position], reals)
    call par_allgather([mine%dt_zone, mine%dt_reason, mine%fail, mine%fail_id, mine%stop, &
        mine%stop_signal], ints)
    do r = 1, par_size()
      if (reals(1, r) < ctl%dt .or. (reals(1, r) == ctl%dt .and. ints(1, r) < ctl%dt_zone)) then
        ctl%dt = reals(1, r)
        ctl%dt_zone = ints(1, r)
        ctl%dt_reason = int(ints(2, r))
        ctl%dt_position = reals(2:4, r)
      end if
      ctl%stop = max(ctl%stop, int(ints(5, r)))
      ctl%stop_signal = max(ctl%stop_signal, int(ints(6, r)))
      if (ints(3, r) /= FAIL_NONE .and. ctl%fail == FAIL_NONE) then
        ctl%fail = int(ints(3, r))
        ctl%fail_id = ints(4, r)
        ctl%fail_position = reals(5:7, r)
      end if
    end do
  end subroutine control_reduce

  !> This rank's clean-stop request after a cycle, for control_reduce: rank 0
  !> checks the wall-time budget (plan%wall_stop_due) and, when due, looks for
  !> the STOP file; any rank reports a signal it caught (its number in signum,
  !> 0 for none).
  subroutine control_stop_request(plan, cycle, elapsed, cycle_wall, dump_wall, stop_path, &
      request, signum)
    type(schedule_t), intent(in) :: plan
    integer(i8), intent(in) :: cycle
    real(rk), intent(in) :: elapsed !< seconds since the start of the run
    real(rk), intent(in) :: cycle_wall !< seconds of this cycle
    real(rk), intent(in) :: dump_wall !< seconds of the longest dump so far
    character(len=*), intent(in) :: stop_path !< the STOP file
    integer, intent(out) :: request, signum
    logical :: exists
    request = STOP_NONE
    if (par_rank() == 0) then
      if (plan%wall_stop_due(elapsed, cycle_wall, dump_wall)) request = STOP_WALL
      if (plan%stop_check_due(cycle)) then
        inquire(file=stop_path, exist=exists)
        if (exists) request = STOP_FILE
      end if
    end if
    signum = signal_caught()
    if (signum /= 0) request = STOP_SIGNAL
  end subroutine control_stop_request

  !> The step fell below dt_min: a failure set by the zone of the stable step.
  subroutine control_step_failed(ctl)
    type(control_t), intent(inout) :: ctl
    ctl%fail = FAIL_DT
    ctl%fail_id = ctl%dt_zone
    ctl%fail_position = ctl%dt_position
  end subroutine control_step_failed

end module solver_control
