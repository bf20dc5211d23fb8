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
  use parallel_env, only: par_rank, par_sum_array, par_sum_exact
  use core_exact_sum, only: exact_sum_t, exact_value
  use parallel_route, only: par_min_array
  use solver_schedule, only: schedule_t
  implicit none
  private
  public :: control_reduce, control_stop_request, control_step_failed, control_block_kinetic

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
    real(rk) :: first(4), second(1), payload(9), mine_rank
    integer :: zone, reason, z, n

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
    ! Three reductions of a few numbers each, whatever the rank count (an
    ! all-gather of every rank's record cost O(ranks) per rank and cycle).
    ! Ids, codes and ranks are integers below 2^53: exact as reals.
    ! 1: the smallest step; the largest stop request and signal (as minima
    ! of their negatives); the lowest rank that found a failure.
    mine_rank = huge(1.0_rk)
    if (mine%fail /= FAIL_NONE) mine_rank = real(par_rank(), rk)
    first = [mine%dt, -real(mine%stop, rk), -real(mine%stop_signal, rk), mine_rank]
    call par_min_array(first)
    ctl%dt = first(1)
    ctl%stop = -int(first(2))
    ctl%stop_signal = -int(first(3))
    ! 2: among the ranks with that step, the lowest zone id.
    second = huge(1.0_rk)
    if (mine%dt == ctl%dt) second(1) = real(mine%dt_zone, rk)
    call par_min_array(second)
    ! 3: what the rank holding that zone and the failing rank know; every
    ! other rank adds zeros, so the sums are exact.
    payload = 0.0_rk
    if (mine%dt == ctl%dt .and. real(mine%dt_zone, rk) == second(1)) &
        payload(1:4) = [real(mine%dt_reason, rk), mine%dt_position]
    if (first(4) == real(par_rank(), rk)) payload(5:9) = [real(mine%fail, rk), &
        real(mine%fail_id, rk), mine%fail_position]
    call par_sum_array(payload)
    ctl%dt_zone = int(second(1), i8)
    if (second(1) == huge(1.0_rk)) ctl%dt_zone = 0
    ctl%dt_reason = nint(payload(1))
    ctl%dt_position = payload(2:4)
    if (first(4) < huge(1.0_rk)) then
      ctl%fail = nint(payload(5))
      ctl%fail_id = nint(payload(6), i8)
      ctl%fail_position = payload(7:9)
    end if
  end subroutine control_reduce

  !> Kinetic energy of block b (&control stop_block): each corner's eighth of
  !> the mass of the block's owned zones at its node's velocity (as the
  !> history's per-material columns), summed exactly (core_exact_sum), so the
  !> stop is decided identically on every rank and rank count. Collective.
  function control_block_kinetic(mesh, state, b) result(kinetic)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    integer, intent(in) :: b
    real(rk) :: kinetic
    type(exact_sum_t) :: acc(1)
    integer :: z, k, n
    real(rk) :: v2
    do z = 1, mesh%nzone_owned
      if (mesh%zone_block(z) /= b) cycle
      v2 = 0.0_rk
      do k = 1, 8
        n = mesh%zone_node(k, z)
        v2 = v2 + (state%node_velocity(1, n) * state%node_velocity(1, n) + &
            state%node_velocity(2, n) * state%node_velocity(2, n) + &
            state%node_velocity(3, n) * state%node_velocity(3, n))
      end do
      call acc(1)%add(0.0625_rk * state%zone_mass(z) * v2)
    end do
    call par_sum_exact(acc)
    kinetic = exact_value(acc(1))
  end function control_block_kinetic

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
