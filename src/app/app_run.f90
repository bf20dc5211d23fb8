!> The run: read the deck, set up, the time loop, and the one failure path
!> (flag reduced every cycle, collective final dump, non-zero exit). Only
!> orchestration: the cycle is solver_cycle (src/solver), what is due when is
!> schedule_t, the output routines are io_output and io_history.
module app_run
  use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
  use core_kinds, only: rk, i8
  use core_status, only: status_t
  use core_timer, only: wall_time, timers_t
  use core_malloc, only: malloc_setup_policy, malloc_loop_policy
  use mesh_local, only: mesh_t
  use hydro_state, only: state_t
  use hydro_boundary, only: boundary_t
  use hydro_driver, only: material_zones_t, hydro_zone_update
  use contact_enforce, only: contact_t, contact_report, side_context_t
  use contact_monitor, only: contact_audit_due
  use solver_step, only: solver_cycle, solver_audit, solver_contact_refresh
  use solver_schedule, only: schedule_t
  use solver_fault, only: inject_nan, inject_tangle
  use solver_control, only: control_t, control_reduce, control_stop_request, &
      control_step_failed, control_block_kinetic, FAIL_NONE, STOP_NONE
  use solver_eta, only: eta_t
  use io_deck, only: config_t, deck_read, output_directory_create
  use io_h5, only: h5_library_open, h5_library_close
  use io_history, only: history_open, history_sums
  use io_probe, only: probes_t, probe_open, probe_sample
  use io_output, only: output_dump, output_history, status_line, input_errors_report, &
      setup_echo, failure_message, max_cycles_message, stop_message, audit_stop_message, &
      timing_report, halo_report, kinetic_stop_message
  use parallel_env, only: par_sum, par_rank, par_bcast
  use app_provenance, only: restart_deck_check
  use app_setup, only: setup_run, setup_sides
  use app_summary, only: model_speed_check, model_summary
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
    integer :: bad, ierr, k, policy
    logical :: deck_ok, setup_failed
    character(len=600), allocatable :: summary(:)
    real(rk) :: wall_begin, sums(5)
    real(rk), allocatable :: per_material(:, :)

    ! The wall-time limit counts from here: set-up and the restart read included.
    wall_begin = wall_time()
    policy = 0
    ! The report's sections, in the same order on every rank.
    call timers%add('set-up')
    call timers%add('mesh generate', within='set-up')
    call timers%add('dual graph', within='set-up')
    call timers%add('partition', within='set-up')
    call timers%add('migrate', within='set-up')
    call timers%add('halo plans', within='set-up')
    call timers%add('contact set-up', within='set-up')
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
    ! A deck that reads a mesh file keeps malloc's mmap threshold at 128 kB
    ! through the set-up (unless the environment sets it): the reader's
    ! freed temporaries must not leave the partition and migration a
    ! fragmented heap (core_malloc.c). It costs set-up time (each large block
    ! mapped afresh), which a generated mesh, whose whole-run share holds its
    ! bound without it, does not pay.
    if (status%ok()) then
      if (any(config%parts%mesh_file /= '')) call malloc_setup_policy(policy)
    end if
    deck_ok = status%ok()
    restart = config%restart
    if (len_trim(restart_path) > 0) restart = restart_path
    ! With deck errors the set-up does not run; the restart dump's deck is
    ! still compared (a changed key is often the cause of the errors).
    if (.not. deck_ok .and. ierr == 0 .and. len_trim(restart) > 0) &
        call restart_check_anyway(restart, config, force, status)
    if (status%ok()) call setup_run(config, restart, force, mesh, bc, state, mz, ct, probes, &
        timers, status)
    setup_failed = deck_ok .and. .not. status%ok()
    if (status%ok() .and. len_trim(restart) == 0) call model_speed_check(config, mesh, state, &
        status)
    if (status%ok()) call setup_echo(config, mesh, restart)
    if (status%ok()) then
      call model_summary(config, mesh, state, probes, summary)
      if (par_rank() == 0) write(output_unit, '(a)') (trim(summary(k)), k = 1, size(summary))
    end if
    if (status%ok() .and. .not. check_only) call output_directory_create( &
        config%output%directory, status)
    if (.not. status%ok()) call input_errors_report(status)
    ! The checks that need the mesh did not run: say so.
    if (.not. deck_ok .and. par_rank() == 0 .and. ierr == 0) write(error_unit, '(a)') &
        'impact3d: not checked because of the deck errors above: the mesh (parts, '// &
        'blocks of mesh files, face sets named by &boundary and &contact), the probes, the '// &
        'initial node speeds and the model summary'
    if (deck_ok .and. setup_failed .and. par_rank() == 0) write(error_unit, '(a)') &
        'impact3d: set-up stopped at the first stage with errors; the later stages were '// &
        'not checked (in order: mesh parts and blocks, &boundary and &contact face sets, '// &
        'initial contact overlaps, initial state, probes, contact set-up, initial node speeds)'
    if (.not. status%ok() .or. check_only) then
      if (status%ok()) code = EXIT_OK
      return
    end if

    call hydro_zone_update(mesh, state, config%materials, mz, config%hydro, bc, &
        state%node_position, state%node_velocity, bad)
    call control_reduce(mesh, state, config%hydro, bad, FAIL_NONE, ctl)
    if (contact_audit_due(ct, .true.)) call solver_audit(ct, state, timers)
    if (len_trim(restart) == 0) then
      ! The run's first stable step: the reference of &erosion dt_fraction.
      state%dt_reference = ctl%dt
      if (config%stop_block_index > 0) state%stop_kinetic_initial = &
          control_block_kinetic(mesh, state, config%stop_block_index)
    else if (config%stop_block_index > 0 .and. state%stop_kinetic_initial == 0.0_rk) then
      ! stop_block added at the restart: the reference is the block's energy now.
      state%stop_kinetic_initial = control_block_kinetic(mesh, state, config%stop_block_index)
    end if
    if (len_trim(restart) == 0) then
      allocate(per_material(4, size(config%materials)))
      call history_sums(config, mesh, state, sums, per_material)
      state%energy_initial = sums(1) + sums(2)
    end if
    call history_open(config, state, len_trim(restart) > 0)
    call probe_open(probes, state, len_trim(restart) > 0)
    if (len_trim(restart) == 0) then
      call output_history(config, mesh, state, ct, timers)
      call probe_sample(probes, state)
    end if
    call timers%stop('set-up')
    ! The loop's large temporaries from the heap, not mapped every cycle.
    call malloc_loop_policy(policy)
    call time_loop(config, mesh, state, mz, bc, ct, ctl, probes, len_trim(restart) > 0, &
        wall_begin, timers, code)
    call h5_library_close(ierr, msg)
  end subroutine run_deck

  !> The comparison of the deck with the restart dump's, when the deck has
  !> errors (setup_run, which makes it otherwise, does not run then): its
  !> problems are added to status.
  subroutine restart_check_anyway(restart, config, force, status)
    character(len=*), intent(in) :: restart
    type(config_t), intent(in) :: config
    logical, intent(in) :: force
    type(status_t), intent(inout) :: status
    type(status_t) :: own
    logical :: exists
    integer :: i
    if (.not. allocated(config%deck_text)) return
    exists = .false.
    if (par_rank() == 0) inquire(file=restart, exist=exists)
    call par_bcast(exists)
    if (.not. exists) return
    call restart_deck_check(restart, config, force, own)
    do i = 1, own%count
      if (i <= size(own%messages)) then
        call status%add(trim(own%messages(i)))
      else
        call status%add('restart: (message kept on rank 0 only)')
      end if
    end do
  end subroutine restart_check_anyway

  !> The time loop: step, checks, output when due; ends at t_end, at
  !> max_cycles, on a clean stop or on a failure.
  subroutine time_loop(config, mesh, state, mz, bc, ct, ctl, probes, restarted, wall_begin, &
      timers, code)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(inout) :: state
    type(material_zones_t), intent(inout) :: mz
    type(boundary_t), intent(inout) :: bc
    type(contact_t), intent(inout) :: ct
    type(control_t), intent(inout) :: ctl
    type(probes_t), intent(inout) :: probes
    logical, intent(in) :: restarted
    real(rk), intent(in) :: wall_begin !< start of the run, for the wall-time limit
    type(timers_t), intent(inout) :: timers
    integer, intent(out) :: code
    real(rk) :: dt, wall_start, wall_status, wall_cycle, wall_dump, kinetic
    integer(i8) :: cycle_status
    integer :: bad, bad_half, request, signum
    logical :: ok, kinetic_stop
    character(len=8) :: dump_why
    type(eta_t) :: eta
    type(schedule_t) :: plan
    type(side_context_t) :: sides

    code = EXIT_OK
    sides = setup_sides(config)
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
    kinetic_stop = .false.

    do while (code == EXIT_OK)
      if (ctl%fail /= FAIL_NONE) then
        call failure_message(config, mesh, state, ctl)
        call output_dump(config, mesh, state, ct, 'failure', wall_start, timers, ok)
        code = EXIT_FAILURE
        exit
      end if
      if (state%time >= config%t_end) exit
      ! &control stop_block: ends like t_end (final dump, exit 0).
      if (kinetic_stop) then
        call kinetic_stop_message(config, state, kinetic)
        exit
      end if
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
          bad_half, bad, timers, config%failures, config%erosion, sides)
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
      if (config%stop_block_index > 0) then
        kinetic = control_block_kinetic(mesh, state, config%stop_block_index)
        kinetic_stop = kinetic < config%stop_kinetic_fraction * state%stop_kinetic_initial
      end if
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
    ! A clean stop (max_cycles, STOP file, wall-time limit, a signal) reports
    ! its timing like a run that reached t_end; a failure does not.
    if (code == EXIT_OK) then
      call output_dump(config, mesh, state, ct, 'final', wall_start, timers, ok)
      if (.not. ok) code = EXIT_FAILURE
    end if
    if (code /= EXIT_OK .and. code /= EXIT_INCOMPLETE) return
    call contact_report(ct, wall_time() - wall_start - &
        timers%total('dumps'))
    call halo_report(mesh, state%cycle)
    call timing_report(timers, state%cycle, wall_time() - wall_start)
  end subroutine time_loop

end module app_run
