!> The run: read the deck, set up, the predictor-corrector time loop, output,
!> and the one failure path (flag reduced every cycle, collective final dump,
!> MPI finalized, non-zero exit).
module app_run
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_value, ieee_quiet_nan
  use core_kinds, only: rk, i8
  use core_status, only: status_t
  use core_timer, only: wall_time, timer_t
  use core_signal, only: signal_caught, signal_name
  use mesh_global, only: global_mesh_t
  use mesh_local, only: mesh_t
  use mesh_geometry, only: hex_centroid
  use hydro_state, only: state_t, HOURGLASS_STIFFNESS
  use hydro_boundary, only: boundary_t
  use hydro_kernels, only: DT_CFL, DT_VOLUME
  use hydro_driver, only: material_zones_t, hydro_zone_update, hydro_forces, &
      hydro_energy_update, hydro_velocity_update, hydro_time_step, hydro_energies, &
      hydro_strength_update
  use io_deck, only: config_t, deck_read, output_directory_create
  use io_h5, only: h5_library_open, h5_library_close
  use io_dump, only: dump_write, dump_read, dump_series_update, run_info_t
  use core_version, only: IMPACT3D_VERSION
  use app_eta, only: eta_t
  use app_provenance, only: restart_deck_check, command_line
  use app_setup, only: setup_mesh, setup_state
  use contact_enforce, only: contact_t, contact_setup, contact_apply, contact_work_update, &
      contact_report, &
      contact_diagnostics, CONTACT_DIAG_COUNT, CONTACT_DIAG_NAMES
  use contact_monitor, only: contact_initial, contact_audit_run, contact_step_end
  use contact_state, only: initial_offsets_t
  use parallel_env, only: par_rank, par_size, par_allgather, par_sum, par_sum_array, par_bcast, par_max
  implicit none
  private
  public :: run_deck

  integer, parameter, public :: EXIT_OK = 0, EXIT_INPUT = 1, EXIT_FAILURE = 2, EXIT_INCOMPLETE = 3
  integer, parameter :: FAIL_NONE = 0, FAIL_VOLUME = 1, FAIL_NAN = 2, FAIL_DT = 3
  integer, parameter :: NRECORD = 13
  ! Clean-stop requests; the largest over the ranks wins.
  integer, parameter :: STOP_NONE = 0, STOP_FILE = 1, STOP_WALL = 2, STOP_SIGNAL = 3

  !> What the end-of-cycle reduction found.
  type :: control_t
    real(rk) :: dt = huge(1.0_rk) !< stable step
    real(rk) :: dt_zone = 0.0_rk !< global id of the zone that sets it
    real(rk) :: dt_position(3) = 0.0_rk !< and its centroid
    integer :: dt_reason = DT_CFL
    integer :: fail = FAIL_NONE
    real(rk) :: fail_zone = 0.0_rk !< global id (zone or node)
    real(rk) :: fail_position(3) = 0.0_rk
    integer :: stop = STOP_NONE !< a clean stop requested (STOP file, wall-time limit, signal)
    integer :: stop_signal = 0 !< with STOP_SIGNAL: the signal (largest number over the ranks)
  end type control_t

contains

  !> Run the deck; returns the process exit code (same on every rank).
  subroutine run_deck(deck_path, restart_path, check_only, force, code)
    character(len=*), intent(in) :: deck_path, restart_path
    logical, intent(in) :: check_only !< validate the deck and set up, then stop
    logical, intent(in) :: force !< restart even if groups that must not change did
    integer, intent(out) :: code
    type(config_t) :: config
    type(status_t) :: status
    type(global_mesh_t) :: global
    type(mesh_t) :: mesh
    type(boundary_t) :: bc
    type(state_t) :: state
    type(material_zones_t) :: mz
    type(contact_t) :: ct
    type(initial_offsets_t), allocatable :: offsets(:)
    type(control_t) :: ctl
    character(len=256) :: restart
    character(len=400) :: msg
    logical :: exists
    integer :: bad, ierr
    real(rk) :: wall_begin, wall_read

    ! The wall-time limit counts from here: set-up and the restart read included.
    wall_begin = wall_time()
    wall_read = 0.0_rk
    code = EXIT_OK
    call h5_library_open(ierr, msg)
    if (ierr /= 0) then
      call status%add('HDF5: '//trim(msg))
      call report(status)
      code = EXIT_INPUT
      return
    end if
    call deck_read(deck_path, config, status)
    restart = config%restart
    if (len_trim(restart_path) > 0) restart = restart_path
    if (status%ok() .and. len_trim(restart) > 0) then
      exists = .false.
      if (par_rank() == 0) inquire(file=restart, exist=exists)
      call par_bcast(exists)
      if (.not. exists) call status%add('&control: restart: file '''//trim(restart)// &
          ''' does not exist')
      ! Before anything else: the deck against the one the dump was made with.
      if (status%ok()) call restart_deck_check(restart, config, force, status)
    end if
    if (status%ok()) call setup_mesh(config, global, mesh, bc, status)
    ! Initial penetration (may move nodes: before the nodal masses).
    ! (Nested: Fortran does not short-circuit .and., and config%contacts is
    ! not allocated when the deck could not be read.)
    if (status%ok()) then
      if (size(config%contacts) > 0) call contact_initial(config%contacts, global, offsets, &
          status)
    end if
    if (status%ok()) call setup_state(config, global, mesh, bc, state, mz, status)
    if (status%ok()) call contact_setup(config%contacts, global, mesh, state%node_mass, ct, &
        status, offsets)
    if (.not. status%ok()) then
      call report(status)
      code = EXIT_INPUT
      return
    end if
    call global%free()
    if (len_trim(restart) > 0) then
      wall_read = wall_time()
      call dump_read(restart, mesh, state, status)
      wall_read = wall_time() - wall_read
      if (.not. status%ok()) then
        call report(status)
        code = EXIT_INPUT
        return
      end if
    end if
    if (par_rank() == 0) call echo(config, mesh, restart)
    if (check_only) return
    call output_directory_create(config%output%directory, status)
    if (.not. status%ok()) then
      call report(status)
      code = EXIT_INPUT
      return
    end if

    call hydro_zone_update(mesh, state, config%materials, mz, config%hydro, bc, &
        state%node_position, state%node_velocity, bad)
    call end_of_cycle_control(mesh, state, config, bad, FAIL_NONE, ctl)
    if (ct%npair > 0) then
      allocate(state%node_contact_gap(size(state%node_position, 2)))
      state%node_contact_gap = 0.0_rk
      call audit(ct, state)
    end if
    if (len_trim(restart) == 0) then
      state%energy_initial = total_energy(mesh, state)
      call history_open(config, state, .false.)
      call history_write(config, mesh, state, ct)
    else
      call history_open(config, state, .true.)
    end if
    call time_loop(config, mesh, state, mz, bc, ct, ctl, len_trim(restart) > 0, wall_begin, &
        wall_read, code)
    call h5_library_close(ierr, msg)
  end subroutine run_deck

  !> Rank 0 prints every input problem at once.
  subroutine report(status)
    type(status_t), intent(in) :: status
    integer :: i
    if (par_rank() /= 0) return
    do i = 1, min(status%count, size(status%messages))
      write(error_unit, '(a)') 'input error: '//trim(status%messages(i))
    end do
    write(error_unit, '(a,i0,a)') 'impact3d: ', status%count, &
        ' input error(s); nothing was run'
  end subroutine report

  !> Echo the effective set-up.
  subroutine echo(config, mesh, restart)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: restart
    write(output_unit, '(a)') 'impact3d: '//trim(config%title)
    write(output_unit, '(a,i0,a,i0,a,i0,a)') '  mesh: ', mesh%nzone_global, ' zones, ', &
        mesh%nnode_global, ' nodes on ', par_size(), ' rank(s)'
    write(output_unit, '(a,es12.5,a,f6.3,a,f6.3,a,f6.3)') '  t_end = ', config%t_end, &
        '  cfl = ', config%hydro%cfl, '  q_linear = ', config%hydro%q_linear, &
        '  q_quadratic = ', config%hydro%q_quadratic
    if (len_trim(restart) > 0) write(output_unit, '(a)') '  restart from '//trim(restart)
    flush(output_unit)
  end subroutine echo

  real(rk) function total_energy(mesh, state)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    real(rk) :: sums(5)
    call hydro_energies(mesh, state, sums)
    total_energy = par_sum(sums(1)) + par_sum(sums(2))
  end function total_energy

  !> Local checks, local stable step, one collective: every rank learns the
  !> global step (ties to the lowest zone id) and the first failure.
  subroutine end_of_cycle_control(mesh, state, config, bad, bad_kind, ctl, stop_request, &
      stop_signal)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(config_t), intent(in) :: config
    integer, intent(in) :: bad !< local zone with bad volume (0 = none) from the last update
    integer, intent(in) :: bad_kind !< FAIL_VOLUME from an earlier stage, else FAIL_NONE
    type(control_t), intent(out) :: ctl
    integer, intent(in), optional :: stop_request !< this rank's STOP_* request
    integer, intent(in), optional :: stop_signal !< with STOP_SIGNAL: the signal this rank caught
    real(rk) :: record(NRECORD), dt
    real(rk), allocatable :: all(:, :)
    integer :: zone, reason, z, n, r, fail
    real(rk) :: where(3), gid

    call hydro_time_step(mesh, state, config%hydro, dt, zone, reason)
    fail = FAIL_NONE
    gid = 0.0_rk
    where = 0.0_rk
    if (bad > 0 .or. bad_kind /= FAIL_NONE) then
      fail = FAIL_VOLUME
      z = max(bad, 1)
      gid = real(mesh%zone_gid(z), rk)
      ! Where the zone was at the start of the cycle (its new corners may be garbage).
      where = hex_centroid(state%node_position_old(:, mesh%zone_node(:, z)))
    else
      do z = 1, mesh%nzone_owned
        if (ieee_is_nan(state%zone_energy(z))) then
          fail = FAIL_NAN
          gid = real(mesh%zone_gid(z), rk)
          where = hex_centroid(state%node_position(:, mesh%zone_node(:, z)))
          exit
        end if
      end do
      if (fail == FAIL_NONE) then
        do n = 1, mesh%nnode_owned
          if (any(ieee_is_nan(state%node_velocity(:, n)))) then
            fail = FAIL_NAN
            gid = -real(mesh%node_gid(n), rk)
            where = state%node_position(:, n)
            exit
          end if
        end do
      end if
    end if
    record = [dt, 0.0_rk, real(reason, rk), real(fail, rk), gid, where, 0.0_rk, 0.0_rk, 0.0_rk, &
        0.0_rk, 0.0_rk]
    if (present(stop_request)) record(12) = real(stop_request, rk)
    if (present(stop_signal)) record(13) = real(stop_signal, rk)
    if (zone > 0) then
      record(2) = real(mesh%zone_gid(zone), rk)
      record(9:11) = hex_centroid(state%node_position(:, mesh%zone_node(:, zone)))
    end if
    allocate(all(NRECORD, par_size()))
    call par_allgather(record, all)
    do r = 1, par_size()
      if (all(1, r) < ctl%dt .or. (all(1, r) == ctl%dt .and. all(2, r) < ctl%dt_zone)) then
        ctl%dt = all(1, r)
        ctl%dt_zone = all(2, r)
        ctl%dt_reason = nint(all(3, r))
        ctl%dt_position = all(9:11, r)
      end if
      ctl%stop = max(ctl%stop, nint(all(12, r)))
      ctl%stop_signal = max(ctl%stop_signal, nint(all(13, r)))
      if (nint(all(4, r)) /= FAIL_NONE .and. ctl%fail == FAIL_NONE) then
        ctl%fail = nint(all(4, r))
        ctl%fail_zone = all(5, r)
        ctl%fail_position = all(6:8, r)
      end if
    end do
  end subroutine end_of_cycle_control

  !> The predictor-corrector loop.
  subroutine time_loop(config, mesh, state, mz, bc, ct, ctl, restarted, wall_begin, wall_read, &
      code)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(inout) :: state
    type(material_zones_t), intent(in) :: mz
    type(boundary_t), intent(inout) :: bc
    type(contact_t), intent(inout) :: ct
    type(control_t), intent(inout) :: ctl
    logical, intent(in) :: restarted
    real(rk), intent(in) :: wall_begin !< start of the run, for the wall-time limit
    real(rk), intent(in) :: wall_read !< seconds the restart read took (0 for a new run)
    integer, intent(out) :: code
    real(rk) :: dt, dt_stable, next_dump, work, wall_start, wall_status, work_sum, contact_work
    real(rk) :: wall_output, wall_mark, halo_max
    integer(i8) :: cycle_status
    integer :: bad, bad_half
    logical :: last, dump_now, ok, exists, audit_now
    integer :: request, signum
    real(rk) :: wall_cycle_start, cycle_wall, wall_dump
    character(len=16) :: reason
    type(timer_t) :: halo
    type(eta_t) :: eta

    code = EXIT_OK
    wall_start = wall_time()
    call eta%add(wall_start, state%time)
    wall_status = wall_start
    wall_output = 0.0_rk
    ! Until the loop has written a dump, the time of a dump is estimated by the
    ! initial dump or, after a restart, by the read of the restart dump.
    wall_dump = wall_read
    cycle_status = state%cycle
    if (.not. restarted) then
      wall_mark = wall_time()
      call write_dump(config, mesh, state, 'initial', wall_start, ok)
      wall_output = wall_time() - wall_mark
      wall_dump = wall_output
      if (.not. ok) then
        code = EXIT_FAILURE
        return
      end if
    end if
    next_dump = huge(1.0_rk)
    if (config%output%dump_interval > 0.0_rk) next_dump = config%output%dump_interval * &
        (aint(state%time / config%output%dump_interval + 1.0e-9_rk) + 1.0_rk)

    do
      if (ctl%fail /= FAIL_NONE) then
        call fail_stop(config, mesh, state, ctl, wall_start)
        code = EXIT_FAILURE
        return
      end if
      if (state%time >= config%t_end) exit
      if (state%cycle >= config%max_cycles) then
        if (par_rank() == 0) write(error_unit, '(a,i0,a,es12.5,a)') &
            'impact3d: stopped at max_cycles = ', config%max_cycles, ' before t_end (t = ', &
            state%time, '); the last dump is a restart point'
        call write_dump(config, mesh, state, 'max_cycles', wall_start, ok)
        code = EXIT_INCOMPLETE
        return
      end if

      ! Step: stability, growth, largest step, then exact landing on dumps and t_end.
      dt_stable = min(ctl%dt, config%hydro%dt_max)
      if (state%dt_previous > 0.0_rk) then
        dt_stable = min(dt_stable, config%hydro%dt_growth * state%dt_previous)
      else if (config%hydro%dt_initial > 0.0_rk) then
        dt_stable = min(dt_stable, config%hydro%dt_initial)
      end if
      dt = dt_stable
      last = .false.
      dump_now = .false.
      if (config%t_end - state%time <= dt * (1.0_rk + 1.0e-9_rk)) then
        dt = config%t_end - state%time
        last = .true.
      end if
      if (next_dump - state%time <= dt * (1.0_rk + 1.0e-9_rk)) then
        dt = next_dump - state%time
        dump_now = .true.
      end if
      if (dt < config%hydro%dt_min .and. .not. (last .or. dump_now)) then
        ctl%fail = FAIL_DT
        ctl%fail_zone = ctl%dt_zone
        ctl%fail_position = ctl%dt_position
        cycle
      end if
      state%dt = dt
      wall_cycle_start = wall_time()

      if (state%cycle + 1 == config%fault_cycle .and. config%fault_kind == 'tangle') &
          call inject_tangle(mesh, state)
      call step(config, mesh, state, mz, bc, ct, dt, bad_half, bad, work, contact_work, halo)
      state%boundary_work = state%boundary_work + par_sum(work)
      if (ct%npair > 0) then
        state%contact_work = state%contact_work + par_sum(contact_work)
        call contact_step_end(ct)
      end if
      state%time = state%time + dt
      if (last) state%time = config%t_end
      if (dump_now .and. abs(state%time - next_dump) <= 1.0e-9_rk * dt) state%time = next_dump
      state%cycle = state%cycle + 1
      state%dt_previous = dt_stable
      ! The contact audit: after every global search and before every dump.
      if (ct%npair > 0) then
        audit_now = ct%audit_due .or. dump_now .or. last
        if (config%output%dump_cycles > 0) audit_now = audit_now .or. &
            mod(state%cycle, int(config%output%dump_cycles, i8)) == 0
        if (audit_now) call audit(ct, state)
        if (ct%stop_run) then
          if (par_rank() == 0) write(error_unit, '(a)') '  writing a final dump and stopping'
          call history_write(config, mesh, state, ct)
          call write_dump(config, mesh, state, 'failure', wall_start, ok)
          code = EXIT_FAILURE
          return
        end if
      end if

      if (state%cycle == config%fault_cycle .and. config%fault_kind == 'nan') &
          call inject_nan(mesh, state)
      ! Batch use: rank 0 decides on a clean stop for the STOP file and the
      ! wall-time limit (budget: three cycles, two dumps and a second), any rank
      ! for a signal it caught; the requests travel with the cycle's control
      ! reduction, so a signal delivered to one rank stops them all.
      request = STOP_NONE
      if (par_rank() == 0) then
        cycle_wall = wall_time() - wall_cycle_start
        if (config%wall_limit > 0.0_rk) then
          if (wall_time() - wall_begin + 3.0_rk * cycle_wall + 2.0_rk * wall_dump + 1.0_rk > &
              config%wall_limit) request = STOP_WALL
        end if
        if (mod(state%cycle, int(config%stop_check_every, i8)) == 0) then
          inquire(file=trim(config%output%directory)//'/'//trim(config%stop_file), &
              exist=exists)
          if (exists) request = STOP_FILE
        end if
      end if
      signum = signal_caught()
      if (signum /= 0) request = STOP_SIGNAL
      if (bad_half > 0) then
        call end_of_cycle_control(mesh, state, config, bad_half, FAIL_VOLUME, ctl, request, &
            signum)
      else
        call end_of_cycle_control(mesh, state, config, bad, FAIL_NONE, ctl, request, signum)
      end if
      if (ctl%fail /= FAIL_NONE) cycle
      if (ctl%stop /= STOP_NONE .and. .not. last) then
        call history_write(config, mesh, state, ct)
        if (par_rank() == 0) then
          select case (ctl%stop)
          case (STOP_FILE)
            write(output_unit, '(a)') 'impact3d: stop file '''//trim(config%output%directory)// &
                '/'//trim(config%stop_file)//''' found: writing a restart dump and stopping '// &
                '(remove the file before restarting)'
          case (STOP_WALL)
            write(output_unit, '(a)') 'impact3d: close to the wall-time limit ('// &
                seconds(wall_time() - wall_begin)//' s of wall_limit = '// &
                seconds(config%wall_limit)//' s used): writing a restart dump and stopping'
          case default
            write(output_unit, '(a)') 'impact3d: signal '//trim(signal_name(ctl%stop_signal))// &
                ' received: writing a restart dump and stopping'
          end select
          flush(output_unit)
        end if
        call write_dump(config, mesh, state, 'stop', wall_start, ok)
        code = EXIT_INCOMPLETE
        if (.not. ok) code = EXIT_FAILURE
        if (par_rank() == 0 .and. ok) write(output_unit, '(a,i0,a)') &
            'impact3d: stopped at cycle ', state%cycle, ' with a restart dump, '// &
            seconds(wall_time() - wall_begin)//' s after the start; exit code 3'
        return
      end if

      if (mod(state%cycle, int(config%output%history_every, i8)) == 0 .or. last) &
          call history_write(config, mesh, state, ct)
      if (mod(state%cycle, int(config%output%status_every, i8)) == 0 .or. last) then
        work_sum = real(mesh%nzone_global, rk) * real(state%cycle - cycle_status, rk)
        select case (ctl%dt_reason)
        case (DT_VOLUME)
          reason = 'volume'
        case default
          reason = 'cfl'
        end select
        call eta%add(wall_time(), state%time)
        call status_line(config, mesh, state, ctl, trim(reason), &
            work_sum / max(wall_time() - wall_status, 1.0e-9_rk), wall_start, eta)
        wall_status = wall_time()
        cycle_status = state%cycle
      end if
      wall_mark = wall_time()
      if (dump_now) then
        next_dump = next_dump + config%output%dump_interval
        if (.not. last) call write_dump(config, mesh, state, 'interval', wall_start, ok)
        if (.not. ok) then
          code = EXIT_FAILURE
          return
        end if
      else if (config%output%dump_cycles > 0 .and. .not. last) then
        if (mod(state%cycle, int(config%output%dump_cycles, i8)) == 0) then
          call write_dump(config, mesh, state, 'cycles', wall_start, ok)
          if (.not. ok) then
            code = EXIT_FAILURE
            return
          end if
        end if
      end if
      wall_dump = max(wall_dump, wall_time() - wall_mark)
      wall_output = wall_output + (wall_time() - wall_mark)
    end do
    call write_dump(config, mesh, state, 'final', wall_start, ok)
    if (.not. ok) then
      code = EXIT_FAILURE
      return
    end if
    halo_max = par_max(halo%total)
    if (par_rank() == 0) write(output_unit, '(a,f10.3,a)') 'impact3d: node halo exchange ', &
        halo_max, ' s (largest over the ranks)'
    if (ct%npair > 0) call contact_report(ct, wall_time() - wall_start - wall_output)
    if (par_rank() == 0) write(output_unit, '(a,i0,a,f10.3,a,f8.3,a)') 'impact3d: done, ', &
        state%cycle, ' cycles, ', wall_time() - wall_start, ' s (', wall_output, &
        ' s of it in dumps)'
  end subroutine time_loop

  !> Seconds as text with two decimals, no leading blanks ('0.13', '3600.00').
  function seconds(value) result(text)
    real(rk), intent(in) :: value
    character(len=:), allocatable :: text
    character(len=24) :: buffer
    write(buffer, '(f24.2)') value
    text = trim(adjustl(buffer))
  end function seconds

  !> The contact audit at x^n of the state; its gaps go to the dumps.
  subroutine audit(ct, state)
    type(contact_t), intent(inout) :: ct
    type(state_t), intent(inout) :: state
    real(rk) :: t0
    t0 = wall_time()
    call contact_audit_run(ct, state%node_position, state%cycle, state%time)
    ct%audit_seconds = ct%audit_seconds + (wall_time() - t0)
    state%node_contact_gap = 0.0_rk
    state%node_contact_gap(ct%own_local) = ct%gap_own
  end subroutine audit

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

  !> One predictor-corrector cycle from t^n to t^n+1.
  subroutine step(config, mesh, state, mz, bc, ct, dt, bad_half, bad, work, contact_work, halo)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(inout) :: state
    type(material_zones_t), intent(in) :: mz
    type(boundary_t), intent(inout) :: bc
    type(contact_t), intent(inout) :: ct
    real(rk), intent(in) :: dt
    integer, intent(out) :: bad_half, bad
    real(rk), intent(out) :: work !< boundary work of the step (local)
    real(rk), intent(out) :: contact_work !< contact work of the step (local)
    type(timer_t), intent(inout) :: halo !< time in the node halo exchanges
    real(rk) :: unused
    integer :: n
    logical :: strength

    state%node_position_old = state%node_position
    state%node_velocity_old = state%node_velocity
    state%zone_energy_old = state%zone_energy

    strength = allocated(state%zone_stress)

    ! Predictor: forces at t^n, half-step velocities, geometry and EOS at t^n+1/2.
    if (strength) then
      call hydro_forces(mesh, state, config%hydro, bc, state%node_position, &
          state%node_velocity, 0.0_rk, state%zone_stress)
    else
      call hydro_forces(mesh, state, config%hydro, bc, state%node_position, &
          state%node_velocity, 0.0_rk)
    end if
    ! Contact acts on the predictor's half step too, as the rigid wall does:
    ! otherwise the half-step geometry interpenetrates freely and the contact
    ! pressure lags half a step (the mirror test shows it).
    if (ct%npair > 0) call contact_apply(ct, state%node_position_old, state%node_velocity_old, &
        state%node_force, 0.5_rk * dt, state%cycle + 1, .false., wall_time)
    call hydro_velocity_update(mesh, state, bc, 0.5_rk * dt, state%node_velocity_half, unused)
    call halo%start()
    call mesh%node_halo%exchange(state%node_velocity_half)
    call halo%stop()
    do n = 1, mesh%nnode
      state%node_position(:, n) = state%node_position_old(:, n) + 0.5_rk * dt * &
          state%node_velocity_half(:, n)
    end do
    call hydro_energy_update(mesh, state, state%node_velocity_half, 0.5_rk * dt)
    call hydro_zone_update(mesh, state, config%materials, mz, config%hydro, bc, &
        state%node_position, state%node_velocity_half, bad_half)
    if (strength) call hydro_strength_update(mesh, state, config%materials, mz, &
        state%node_velocity_half, 0.5_rk * dt, state%zone_stress, state%zone_stress_half, .false.)

    ! Corrector: forces at t^n+1/2, final velocities, positions and energies.
    if (strength) then
      call hydro_forces(mesh, state, config%hydro, bc, state%node_position, &
          state%node_velocity_half, dt, state%zone_stress_half)
    else
      call hydro_forces(mesh, state, config%hydro, bc, state%node_position, &
          state%node_velocity_half, dt)
    end if
    ! Contact on the final update, boundary conditions re-imposed after it.
    contact_work = 0.0_rk
    if (ct%npair > 0) call contact_apply(ct, state%node_position_old, state%node_velocity_old, &
        state%node_force, dt, state%cycle + 1, .true., wall_time)
    call hydro_velocity_update(mesh, state, bc, dt, state%node_velocity, work)
    if (ct%npair > 0) call contact_work_update(ct, state%node_velocity_old, &
        state%node_velocity, dt, contact_work)
    call halo%start()
    call mesh%node_halo%exchange(state%node_velocity)
    call halo%stop()
    do n = 1, mesh%nnode
      state%node_velocity_half(:, n) = 0.5_rk * (state%node_velocity_old(:, n) + &
          state%node_velocity(:, n))
      state%node_position(:, n) = state%node_position_old(:, n) + dt * &
          state%node_velocity_half(:, n)
    end do
    call hydro_energy_update(mesh, state, state%node_velocity_half, dt)
    ! Deviatoric stress over the whole step: mid-step geometry, mean velocity.
    if (strength) then
      state%zone_stress_half = state%zone_stress
      call hydro_strength_update(mesh, state, config%materials, mz, &
          state%node_velocity_half, dt, state%zone_stress_half, state%zone_stress, .true.)
    end if
    if (config%hydro%hourglass == HOURGLASS_STIFFNESS) state%zone_hourglass = &
        state%zone_hourglass_new
    call hydro_zone_update(mesh, state, config%materials, mz, config%hydro, bc, &
        state%node_position, state%node_velocity, bad)
  end subroutine step

  subroutine write_dump(config, mesh, state, why, wall_start, ok)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(in) :: state
    character(len=*), intent(in) :: why
    real(rk), intent(in) :: wall_start
    logical, intent(out) :: ok !< false when the dump could not be written (same on all ranks)
    type(status_t) :: status
    type(run_info_t) :: info
    character(len=512) :: path
    character(len=:), allocatable :: names
    integer :: b

    write(path, '(a,"/",a,"_",i6.6,".h5")') trim(config%output%directory), &
        trim(config%output%prefix), state%cycle
    if (why == 'failure') write(path, '(a,"/",a,"_",i6.6,"_failed.h5")') &
        trim(config%output%directory), trim(config%output%prefix), state%cycle
    info%wall_seconds = wall_time() - wall_start
    info%reason = why
    info%version = IMPACT3D_VERSION
    info%command = command_line()
    info%deck = config%deck_text
    names = ''
    do b = 1, size(config%blocks)
      if (b > 1) names = names//','
      names = names//trim(config%blocks(b)%name)
    end do
    call dump_write(trim(path), config%title, 'consistent (decks: cm g us Mbar)', names, &
        mesh, state, info, status)
    ok = status%ok()
    if (.not. ok) then
      if (par_rank() == 0) write(error_unit, '(a)') 'error: '//trim(status%messages(1))
      return
    end if
    call dump_series_update(trim(config%output%directory)//'/'//trim(config%output%prefix), &
        trim(path), config%title, state%cycle, state%time, mesh%nnode_global, mesh%nzone_global, &
        allocated(state%zone_stress), allocated(state%node_contact_gap))
    if (par_rank() == 0) write(output_unit, '(a)') '  dump '//trim(path)
  end subroutine write_dump

  !> The single failure path: message, collective final dump, caller exits non-zero.
  subroutine fail_stop(config, mesh, state, ctl, wall_start)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(in) :: state
    type(control_t), intent(in) :: ctl
    real(rk), intent(in) :: wall_start
    character(len=64) :: what
    logical :: ok
    if (par_rank() == 0) then
      select case (ctl%fail)
      case (FAIL_VOLUME)
        what = 'zero or negative volume in zone'
      case (FAIL_NAN)
        if (ctl%fail_zone < 0.0_rk) then
          what = 'NaN velocity at node'
        else
          what = 'NaN energy in zone'
        end if
      case default
        what = 'time step below dt_min, set by zone'
      end select
      write(error_unit, '(a,1x,i0,a,3es14.6,a,i0,a,es14.6)') 'error: '//trim(what), &
          nint(abs(ctl%fail_zone), i8), ' at (', ctl%fail_position, ') in cycle ', &
          state%cycle, ', time ', state%time
      if (ctl%fail == FAIL_DT) write(error_unit, '(a,es12.5,a,es12.5)') '  dt = ', ctl%dt, &
          ' < dt_min = ', config%hydro%dt_min
      write(error_unit, '(a)') '  writing a final dump and stopping'
      flush(error_unit)
    end if
    call write_dump(config, mesh, state, 'failure', wall_start, ok)
  end subroutine fail_stop

  !> history.txt: a fresh file, or on restart the lines up to the restart cycle.
  subroutine history_open(config, state, restarted)
    type(config_t), intent(in) :: config
    type(state_t), intent(in) :: state
    logical, intent(in) :: restarted
    integer :: unit, ios, n, k, j
    character(len=4096) :: line
    character(len=4096), allocatable :: keep(:)
    character(len=:), allocatable :: header
    integer(i8) :: c
    character(len=:), allocatable :: path
    logical :: exists
    if (par_rank() /= 0) return
    path = trim(config%output%directory)//'/history.txt'
    allocate(keep(0))
    inquire(file=path, exist=exists)
    if (restarted .and. exists) then
      open(newunit=unit, file=path, status='old', action='read')
      read(unit, '(a)', iostat=ios) line
      do
        read(unit, '(a)', iostat=ios) line
        if (ios /= 0) exit
        read(line, *, iostat=ios) c
        if (ios == 0 .and. c <= state%cycle) keep = [keep, line]
      end do
      close(unit)
    end if
    open(newunit=unit, file=path, status='replace', action='write')
    header = '# cycle time dt internal_energy kinetic_energy boundary_work '// &
        'total_energy energy_error momentum_x momentum_y momentum_z contact_work'
    do k = 1, size(config%contacts)
      do j = 1, CONTACT_DIAG_COUNT
        header = header//' '//trim(config%contacts(k)%name)//'_'//trim(CONTACT_DIAG_NAMES(j))
      end do
    end do
    write(unit, '(a)') header
    do n = 1, size(keep)
      write(unit, '(a)') trim(keep(n))
    end do
    close(unit)
  end subroutine history_open

  subroutine history_write(config, mesh, state, ct)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(contact_t), intent(in) :: ct
    real(rk) :: sums(5), total
    integer :: unit, k
    call hydro_energies(mesh, state, sums)
    call par_sum_array(sums)
    if (par_rank() /= 0) return
    total = sums(1) + sums(2)
    open(newunit=unit, file=trim(config%output%directory)//'/history.txt', status='old', &
        position='append', action='write')
    write(unit, '(i0,10(1x,es23.15e3))', advance='no') state%cycle, state%time, state%dt, &
        sums(1), sums(2), state%boundary_work, total, relative_error(total, state), sums(3:5)
    write(unit, '(1x,es23.15e3)', advance='no') state%contact_work
    do k = 1, ct%npair
      write(unit, '(*(1x,es23.15e3))', advance='no') ct%pairs(k)%diag
    end do
    write(unit, '(a)') ''
    close(unit)
  end subroutine history_write

  real(rk) function relative_error(total, state)
    real(rk), intent(in) :: total
    type(state_t), intent(in) :: state
    relative_error = (total - state%boundary_work - state%contact_work - &
        state%energy_initial) / &
        max(abs(state%energy_initial), tiny(1.0_rk))
  end function relative_error

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
        nint(ctl%dt_zone, i8), ')  dE/E=', relative_error(sums(1) + sums(2), state), &
        '  ', rate, ' zone-cycles/s  ', min(100.0_rk, 100.0_rk * state%time / config%t_end), &
        '% done  elapsed '//seconds(wall_time() - wall_start)//' s  ETA '//eta_text
    flush(output_unit)
  end subroutine status_line

end module app_run
