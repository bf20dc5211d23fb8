!> The run: read the deck, set up, the predictor-corrector time loop, output,
!> and the one failure path (flag reduced every cycle, collective final dump,
!> MPI finalized, non-zero exit).
module app_run
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use core_kinds, only: rk, i8
  use core_status, only: status_t
  use core_timer, only: wall_time, timer_t
  use core_signal, only: signal_caught, signal_name
  use mesh_global, only: global_mesh_t
  use mesh_local, only: mesh_t
  use hydro_state, only: state_t
  use hydro_boundary, only: boundary_t
  use hydro_kernels, only: DT_VOLUME
  use hydro_driver, only: material_zones_t, hydro_zone_update, hydro_energies
  use io_deck, only: config_t, deck_read, output_directory_create
  use io_h5, only: h5_library_open, h5_library_close
  use io_dump, only: dump_write, dump_read, dump_series_update, run_info_t
  use io_history, only: history_open, history_write, relative_error
  use io_output, only: status_line, seconds
  use io_probe, only: probes_t, probe_setup, probe_open, probe_sample
  use core_version, only: IMPACT3D_VERSION
  use solver_eta, only: eta_t
  use app_provenance, only: restart_deck_check, command_line
  use app_setup, only: setup_mesh, setup_state
  use solver_step, only: solver_lagrange_step
  use solver_schedule, only: schedule_t
  use solver_fault, only: inject_nan, inject_tangle
  use solver_control, only: control_t, control_reduce, FAIL_NONE, FAIL_VOLUME, FAIL_NAN, &
      FAIL_DT, STOP_NONE, STOP_FILE, STOP_WALL, STOP_SIGNAL
  use contact_enforce, only: contact_t, contact_setup, contact_report
  use contact_monitor, only: contact_initial, contact_audit_run, contact_step_end
  use contact_state, only: initial_offsets_t
  use parallel_env, only: par_rank, par_size, par_sum, par_sum_array, par_bcast, par_max
  implicit none
  private
  public :: run_deck

  integer, parameter, public :: EXIT_OK = 0, EXIT_INPUT = 1, EXIT_FAILURE = 2, EXIT_INCOMPLETE = 3

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
    type(probes_t) :: probes
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
      if (size(config%contacts) > 0) call contact_initial(config%contacts, global, &
          bc%symmetry_planes, offsets, status)
    end if
    if (status%ok()) call setup_state(config, global, mesh, bc, state, mz, status)
    if (status%ok()) call probe_setup(config%probes, global, mesh, config%output%directory, &
        config%units, probes, status)
    if (status%ok()) call contact_setup(config%contacts, global, mesh, state%node_mass, ct, &
        status, offsets, bc%symmetry_planes)
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
    call control_reduce(mesh, state, config%hydro, bad, FAIL_NONE, ctl)
    if (ct%npair > 0) then
      allocate(state%node_contact_gap(size(state%node_position, 2)))
      state%node_contact_gap = 0.0_rk
      call audit(ct, state)
    end if
    if (len_trim(restart) == 0) then
      state%energy_initial = total_energy(mesh, state)
      call history_open(config, state, .false.)
      call history_write(config, mesh, state, ct)
      call probe_open(probes, state, .false.)
      call probe_sample(probes, state)
    else
      call history_open(config, state, .true.)
      call probe_open(probes, state, .true.)
    end if
    call time_loop(config, mesh, state, mz, bc, ct, ctl, probes, len_trim(restart) > 0, &
        wall_begin, wall_read, code)
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

  !> The predictor-corrector loop.
  subroutine time_loop(config, mesh, state, mz, bc, ct, ctl, probes, restarted, wall_begin, &
      wall_read, code)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(inout) :: state
    type(material_zones_t), intent(in) :: mz
    type(boundary_t), intent(inout) :: bc
    type(contact_t), intent(inout) :: ct
    type(control_t), intent(inout) :: ctl
    type(probes_t), intent(inout) :: probes
    logical, intent(in) :: restarted
    real(rk), intent(in) :: wall_begin !< start of the run, for the wall-time limit
    real(rk), intent(in) :: wall_read !< seconds the restart read took (0 for a new run)
    integer, intent(out) :: code
    real(rk) :: dt, work, wall_start, wall_status, work_sum, contact_work
    real(rk) :: wall_output, wall_mark, halo_max
    integer(i8) :: cycle_status
    integer :: bad, bad_half
    logical :: ok, exists, step_ok
    integer :: request, signum
    real(rk) :: wall_cycle_start, cycle_wall, wall_dump
    character(len=16) :: reason
    character(len=8) :: dump_why
    type(timer_t) :: halo
    type(eta_t) :: eta
    type(schedule_t) :: plan

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
    plan = schedule_t(t_end=config%t_end, dt_max=config%hydro%dt_max, &
        dt_min=config%hydro%dt_min, dt_growth=config%hydro%dt_growth, &
        dt_initial=config%hydro%dt_initial, dump_interval=config%output%dump_interval, &
        dump_cycles=config%output%dump_cycles, history_every=config%output%history_every, &
        status_every=config%output%status_every, stop_check_every=config%stop_check_every, &
        wall_limit=config%wall_limit)
    call plan%start(state%time)

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
      call plan%choose_step(ctl%dt, state%dt_previous, state%time, dt, step_ok)
      if (.not. step_ok) then
        ctl%fail = FAIL_DT
        ctl%fail_id = ctl%dt_zone
        ctl%fail_position = ctl%dt_position
        cycle
      end if
      state%dt = dt
      wall_cycle_start = wall_time()

      if (state%cycle + 1 == config%fault_cycle .and. config%fault_kind == 'tangle') &
          call inject_tangle(mesh, state)
      call solver_lagrange_step(config%hydro, config%materials, mesh, state, mz, bc, ct, dt, &
          bad_half, bad, work, contact_work, halo)
      state%boundary_work = state%boundary_work + par_sum(work)
      if (ct%npair > 0) then
        state%contact_work = state%contact_work + par_sum(contact_work)
        call contact_step_end(ct)
      end if
      state%time = plan%land(state%time, dt)
      state%cycle = state%cycle + 1
      state%dt_previous = plan%dt_stable
      ! The contact audit: after every global search and before every dump.
      if (ct%npair > 0) then
        if (ct%audit_due .or. plan%audit_due(state%cycle)) call audit(ct, state)
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
        if (plan%wall_stop_due(wall_time() - wall_begin, cycle_wall, wall_dump)) &
            request = STOP_WALL
        if (plan%stop_check_due(state%cycle)) then
          inquire(file=trim(config%output%directory)//'/'//trim(config%stop_file), &
              exist=exists)
          if (exists) request = STOP_FILE
        end if
      end if
      signum = signal_caught()
      if (signum /= 0) request = STOP_SIGNAL
      if (bad_half > 0) then
        call control_reduce(mesh, state, config%hydro, bad_half, FAIL_VOLUME, ctl, request, &
            signum)
      else
        call control_reduce(mesh, state, config%hydro, bad, FAIL_NONE, ctl, request, signum)
      end if
      if (ctl%fail /= FAIL_NONE) cycle
      call probe_sample(probes, state)
      if (ctl%stop /= STOP_NONE .and. .not. plan%last) then
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

      if (plan%history_due(state%cycle)) call history_write(config, mesh, state, ct)
      if (plan%status_due(state%cycle)) then
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
      dump_why = plan%dump_reason(state%cycle)
      if (len_trim(dump_why) > 0) then
        call write_dump(config, mesh, state, trim(dump_why), wall_start, ok)
        if (.not. ok) then
          code = EXIT_FAILURE
          return
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
    call dump_write(trim(path), config%title, trim(config%units), names, &
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
        if (ctl%fail_id < 0) then
          what = 'NaN velocity at node'
        else
          what = 'NaN energy in zone'
        end if
      case default
        what = 'time step below dt_min, set by zone'
      end select
      write(error_unit, '(a,1x,i0,a,3es14.6,a,i0,a,es14.6)') 'error: '//trim(what), &
          abs(ctl%fail_id), ' at (', ctl%fail_position, ') in cycle ', &
          state%cycle, ', time ', state%time
      if (ctl%fail == FAIL_DT) write(error_unit, '(a,es12.5,a,es12.5)') '  dt = ', ctl%dt, &
          ' < dt_min = ', config%hydro%dt_min
      write(error_unit, '(a)') '  writing a final dump and stopping'
      flush(error_unit)
    end if
    call write_dump(config, mesh, state, 'failure', wall_start, ok)
  end subroutine fail_stop


end module app_run
