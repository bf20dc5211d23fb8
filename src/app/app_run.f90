!> The run: read the deck, set up, the time loop, and the one failure path
!> (flag reduced every cycle, collective final dump, non-zero exit). Only
!> orchestration: the cycle is solver_cycle (src/solver), what is due when is
!> schedule_t, the output routines are io_output and io_history.
module app_run
  use core_kinds, only: rk, i8
  use core_status, only: status_t
  use core_timer, only: wall_time, timers_t
  use mesh_local, only: mesh_t
  use hydro_state, only: state_t
  use hydro_boundary, only: boundary_t
  use hydro_driver, only: material_zones_t, hydro_zone_update, hydro_energies
  use contact_enforce, only: contact_t, contact_report
  use contact_monitor, only: contact_audit_due
  use solver_step, only: solver_cycle, solver_audit
  use solver_schedule, only: schedule_t
  use solver_fault, only: inject_nan, inject_tangle
  use solver_control, only: control_t, control_reduce, control_stop_request, &
      control_step_failed, FAIL_NONE, STOP_NONE
  use solver_eta, only: eta_t
  use io_deck, only: config_t, deck_read, output_directory_create
  use io_h5, only: h5_library_open, h5_library_close
  use io_history, only: history_open
  use io_probe, only: probes_t, probe_open, probe_sample
  use io_output, only: output_dump, output_history, status_line, input_errors_report, &
      setup_echo, failure_message, max_cycles_message, stop_message, audit_stop_message, &
      timing_report
  use parallel_env, only: par_sum
  use app_setup, only: setup_run
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
    type(mesh_t) :: mesh
    type(boundary_t) :: bc
    type(state_t) :: state
    type(material_zones_t) :: mz
    type(contact_t) :: ct
    type(control_t) :: ctl
    type(timers_t) :: timers
    type(probes_t) :: probes
    character(len=256) :: restart
    character(len=400) :: msg
    integer :: bad, ierr
    real(rk) :: wall_begin, sums(5)

    ! The wall-time limit counts from here: set-up and the restart read included.
    wall_begin = wall_time()
    ! The report's sections, in the same order on every rank.
    call timers%add('set-up')
    call timers%add('restart read')
    call timers%add('halo', within='step')
    call timers%add('contact', within='step')
    call timers%add('audit')
    call timers%add('history')
    call timers%add('status')
    call timers%add('dumps')
    call timers%start('set-up')
    code = EXIT_INPUT
    call h5_library_open(ierr, msg)
    if (ierr /= 0) call status%add('HDF5: '//trim(msg))
    if (status%ok()) call deck_read(deck_path, config, status)
    restart = config%restart
    if (len_trim(restart_path) > 0) restart = restart_path
    if (status%ok()) call setup_run(config, restart, force, mesh, bc, state, mz, ct, probes, &
        timers, status)
    if (status%ok()) call setup_echo(config, mesh, restart)
    if (status%ok() .and. .not. check_only) call output_directory_create( &
        config%output%directory, status)
    if (.not. status%ok()) call input_errors_report(status)
    if (.not. status%ok() .or. check_only) then
      if (status%ok()) code = EXIT_OK
      return
    end if

    call hydro_zone_update(mesh, state, config%materials, mz, config%hydro, bc, &
        state%node_position, state%node_velocity, bad)
    call control_reduce(mesh, state, config%hydro, bad, FAIL_NONE, ctl)
    if (contact_audit_due(ct, .true.)) call solver_audit(ct, state, timers)
    if (len_trim(restart) == 0) then
      call hydro_energies(mesh, state, sums)
      state%energy_initial = par_sum(sums(1)) + par_sum(sums(2))
    end if
    call history_open(config, state, len_trim(restart) > 0)
    call probe_open(probes, state, len_trim(restart) > 0)
    if (len_trim(restart) == 0) then
      call output_history(config, mesh, state, ct, timers)
      call probe_sample(probes, state)
    end if
    call timers%stop('set-up')
    call time_loop(config, mesh, state, mz, bc, ct, ctl, probes, len_trim(restart) > 0, &
        wall_begin, timers, code)
    call h5_library_close(ierr, msg)
  end subroutine run_deck

  !> The time loop: step, checks, output when due; ends at t_end, at
  !> max_cycles, on a clean stop or on a failure.
  subroutine time_loop(config, mesh, state, mz, bc, ct, ctl, probes, restarted, wall_begin, &
      timers, code)
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
    type(timers_t), intent(inout) :: timers
    integer, intent(out) :: code
    real(rk) :: dt, wall_start, wall_status, wall_cycle, wall_dump
    integer(i8) :: cycle_status
    integer :: bad, bad_half, request, signum
    logical :: ok
    character(len=8) :: dump_why
    type(eta_t) :: eta
    type(schedule_t) :: plan

    code = EXIT_OK
    wall_start = wall_time()
    call eta%add(wall_start, state%time)
    wall_status = wall_start
    cycle_status = state%cycle
    plan = schedule_t(t_end=config%t_end, dt_max=config%hydro%dt_max, &
        dt_min=config%hydro%dt_min, dt_growth=config%hydro%dt_growth, &
        dt_initial=config%hydro%dt_initial, dump_interval=config%output%dump_interval, &
        dump_cycles=config%output%dump_cycles, history_every=config%output%history_every, &
        status_every=config%output%status_every, stop_check_every=config%stop_check_every, &
        wall_limit=config%wall_limit)
    call plan%start(state%time)
    if (.not. restarted) then
      call output_dump(config, mesh, state, ct, 'initial', wall_start, timers, ok)
      if (.not. ok) code = EXIT_FAILURE
    end if
    ! The wall-time budget's dump estimate: the longest dump so far, at first
    ! the initial dump or, after a restart, the read of the restart dump.
    wall_dump = max(timers%total('dumps'), timers%total('restart read'))

    do while (code == EXIT_OK)
      if (ctl%fail /= FAIL_NONE) then
        call failure_message(config, state, ctl)
        call output_dump(config, mesh, state, ct, 'failure', wall_start, timers, ok)
        code = EXIT_FAILURE
        exit
      end if
      if (state%time >= config%t_end) exit
      if (state%cycle >= config%max_cycles) then
        call max_cycles_message(config, state)
        call output_dump(config, mesh, state, ct, 'max_cycles', wall_start, timers, ok)
        code = EXIT_INCOMPLETE
        exit
      end if

      ! Step: stability, growth, largest step, then exact landing on dumps and t_end.
      call plan%choose_step(ctl%dt, state%dt_previous, state%time, dt, ok)
      if (.not. ok) then
        call control_step_failed(ctl)
        cycle
      end if
      wall_cycle = wall_time()
      if (state%cycle + 1 == config%fault_cycle .and. config%fault_kind == 'tangle') &
          call inject_tangle(mesh, state)
      call solver_cycle(config%hydro, config%materials, mesh, state, mz, bc, ct, plan, dt, &
          bad_half, bad, timers)
      if (ct%stop_run) then
        call audit_stop_message()
        call output_history(config, mesh, state, ct, timers)
        call output_dump(config, mesh, state, ct, 'failure', wall_start, timers, ok)
        code = EXIT_FAILURE
        exit
      end if
      if (state%cycle == config%fault_cycle .and. config%fault_kind == 'nan') &
          call inject_nan(mesh, state)

      ! Batch use: clean-stop requests (STOP file, wall-time limit, a signal on
      ! any rank) travel with the cycle's control reduction.
      call control_stop_request(plan, state%cycle, wall_time() - wall_begin, &
          wall_time() - wall_cycle, wall_dump, trim(config%output%directory)//'/'// &
          trim(config%stop_file), request, signum)
      call control_reduce(mesh, state, config%hydro, merge(bad_half, bad, bad_half > 0), &
          FAIL_NONE, ctl, request, signum)
      if (ctl%fail /= FAIL_NONE) cycle
      call probe_sample(probes, state)
      if (ctl%stop /= STOP_NONE .and. .not. plan%last) then
        call output_history(config, mesh, state, ct, timers)
        call stop_message(config, state, ctl, wall_time() - wall_begin, .false.)
        call output_dump(config, mesh, state, ct, 'stop', wall_start, timers, ok)
        code = merge(EXIT_INCOMPLETE, EXIT_FAILURE, ok)
        if (ok) call stop_message(config, state, ctl, wall_time() - wall_begin, .true.)
        exit
      end if

      if (plan%history_due(state%cycle)) call output_history(config, mesh, state, ct, timers)
      if (plan%status_due(state%cycle)) then
        call eta%add(wall_time(), state%time)
        call status_line(config, mesh, state, ct, ctl, eta, wall_start, wall_status, &
            cycle_status, timers)
      end if
      dump_why = plan%dump_reason(state%cycle)
      if (len_trim(dump_why) > 0) then
        call output_dump(config, mesh, state, ct, trim(dump_why), wall_start, timers, ok)
        if (.not. ok) code = EXIT_FAILURE
        wall_dump = max(wall_dump, timers%last('dumps'))
      end if
    end do
    if (code /= EXIT_OK) return
    call output_dump(config, mesh, state, ct, 'final', wall_start, timers, ok)
    if (.not. ok) then
      code = EXIT_FAILURE
      return
    end if
    call contact_report(ct, wall_time() - wall_start - &
        timers%total('dumps'))
    call timing_report(timers, state%cycle, wall_time() - wall_start)
  end subroutine time_loop

end module app_run
