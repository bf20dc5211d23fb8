!> What the run writes besides the history file: its dumps (numbered, the
!> failure dump, the XDMF series), the status line, the messages of a stop or
!> a failure, the set-up echo, the input-error report and the timing report
!> at the end. Rank 0 prints; every routine here is called by every rank.
module io_output
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use core_kinds, only: rk, i8
  use core_status, only: status_t
  use core_timer, only: wall_time, timers_t
  use core_text, only: fixed_text, to_text
  use core_units, only: unit_of
  use core_unit_checks, only: brief_text
  use material_table, only: EOS_MIE_GRUNEISEN
  use core_version, only: IMPACT3D_VERSION
  use core_signal, only: signal_name
  use mesh_local, only: mesh_t
  use hydro_state, only: state_t
  use hydro_kernels, only: DT_VOLUME
  use hydro_driver, only: hydro_energies
  use contact_enforce, only: contact_t, contact_active_flags, contact_resume_state, &
      contact_offset_values
  use solver_control, only: control_t, FAIL_VOLUME, FAIL_NAN, FAIL_DT, STOP_FILE, STOP_WALL
  use solver_eta, only: eta_t
  use parallel_env, only: par_rank, par_size, par_sum_array, par_max, par_allgather
  use core_memory, only: peak_memory_mb
  use core_sort, only: sort_values
  use io_deck, only: config_t
  use io_dump, only: dump_write, dump_series_update, run_info_t
  use io_history, only: history_write, relative_error
  implicit none
  private
  public :: output_dump, output_history, status_line, command_line
  public :: input_errors_report, setup_echo, failure_message, max_cycles_message
  public :: stop_message, audit_stop_message, timing_report, halo_report, kinetic_stop_message

contains

  !> The program's command line (as the process got it).
  function command_line() result(text)
    character(len=:), allocatable :: text
    integer :: n
    call get_command(length=n)
    allocate(character(len=max(n, 1)) :: text)
    call get_command(text)
  end function command_line

  !> The dump of the state's cycle, <prefix>_CCCCCC.h5 (<prefix>_CCCCCC_failed.h5
  !> for why = 'failure'), with the run's provenance, and the XDMF series
  !> updated. Section 'dumps' of timers. ok is false (on every rank) when the
  !> dump could not be written; rank 0 prints why.
  subroutine output_dump(config, mesh, state, ct, why, wall_start, timers, ok)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(in) :: state
    type(contact_t), intent(in) :: ct !< the contact's gaps and work
    character(len=*), intent(in) :: why
    real(rk), intent(in) :: wall_start !< start of the time loop
    type(timers_t), intent(inout) :: timers
    logical, intent(out) :: ok
    type(status_t) :: status
    type(run_info_t) :: info
    character(len=512) :: path
    character(len=:), allocatable :: names
    integer :: b

    call timers%start('dumps')
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
        mesh, state, info, status, ct%node_gap, ct%work, ct%pairs(:)%work, &
        contact_active_flags(ct, mesh%nnode), contact_resume_state(ct), &
        contact_offset_values(ct, mesh%nnode))
    ok = status%ok()
    if (ok) then
      call dump_series_update(trim(config%output%directory)//'/'//trim(config%output%prefix), &
          trim(path), config%title, state%cycle, state%time, mesh%nnode_global, &
          mesh%nzone_global, allocated(state%zone_stress), allocated(ct%node_gap), &
          allocated(state%zone_damage), allocated(state%zone_alive))
      if (par_rank() == 0) write(output_unit, '(a)') '  dump '//trim(path)
    else if (par_rank() == 0) then
      write(error_unit, '(a)') 'error: '//trim(status%messages(1))
    end if
    call timers%stop('dumps')
  end subroutine output_dump

  !> A history row (io_history), section 'history' of timers.
  subroutine output_history(config, mesh, state, ct, timers)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(contact_t), intent(in) :: ct
    type(timers_t), intent(inout) :: timers
    call timers%start('history')
    call history_write(config, mesh, state, ct)
    call timers%stop('history')
  end subroutine output_history

  !> One status line: cycle, time, step and its limiter, energy error, speed
  !> since the last line (wall_last and cycle_last, updated here), then
  !> progress: percent of t_end, wall time since the start (or restart) and
  !> the time left at the recent rate (eta_t). Section 'status' of timers.
  subroutine status_line(config, mesh, state, ct, ctl, eta, wall_start, wall_last, cycle_last, &
      timers)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(contact_t), intent(in) :: ct !< the contact work of the energy balance
    type(control_t), intent(in) :: ctl
    type(eta_t), intent(in) :: eta
    real(rk), intent(in) :: wall_start
    real(rk), intent(inout) :: wall_last !< wall time of the last status line
    integer(i8), intent(inout) :: cycle_last !< its cycle
    type(timers_t), intent(inout) :: timers
    real(rk) :: sums(5), left, rate
    character(len=:), allocatable :: eta_text, reason
    call timers%start('status')
    rate = real(mesh%nzone_global, rk) * real(state%cycle - cycle_last, rk) / &
        max(wall_time() - wall_last, 1.0e-9_rk)
    reason = 'cfl'
    if (ctl%dt_reason == DT_VOLUME) reason = 'volume'
    call hydro_energies(mesh, state, sums)
    ! The kinetic energy of the nodes erosion took out is still in the balance.
    if (allocated(state%node_eroded_kinetic)) sums(2) = sums(2) + &
        sum(state%node_eroded_kinetic(1:mesh%nnode_owned))
    call par_sum_array(sums)
    if (par_rank() == 0) then
      left = eta%seconds_left(config%t_end)
      eta_text = '?'
      if (left >= 0.0_rk) eta_text = fixed_text(left, 2)//' s'
      write(output_unit, '(a,i8,a,es11.4,a,es10.3,a,a,a,i0,a,es9.2,a,es9.2,a,f5.1,a)') &
          'cycle', state%cycle, '  t=', state%time, '  dt=', state%dt, ' (', reason, &
          ' zone ', ctl%dt_zone, ')  dE/E=', relative_error(sums(1) + sums(2), state, ct%work), &
          '  ', rate, ' zone-cycles/s  ', min(100.0_rk, 100.0_rk * state%time / config%t_end), &
          '% done  elapsed '//fixed_text(wall_time() - wall_start, 2)//' s  ETA '//eta_text
      flush(output_unit)
    end if
    wall_last = wall_time()
    cycle_last = state%cycle
    call timers%stop('status')
  end subroutine status_line

  !> Rank 0 prints every input problem at once.
  subroutine input_errors_report(status)
    type(status_t), intent(in) :: status
    integer :: i
    if (par_rank() /= 0) return
    do i = 1, min(status%count, size(status%messages))
      write(error_unit, '(a)') 'input error: '//trim(status%messages(i))
    end do
    write(error_unit, '(a,i0,a)') 'impact3d: ', status%count, &
        ' input error(s); nothing was run'
  end subroutine input_errors_report

  !> Echo the effective set-up (rank 0).
  subroutine setup_echo(config, mesh, restart)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: restart
    if (par_rank() /= 0) return
    write(output_unit, '(a)') 'impact3d: '//trim(config%title)
    write(output_unit, '(a,i0,a,i0,a,i0,a)') '  mesh: ', mesh%nzone_global, ' zones, ', &
        mesh%nnode_global, ' nodes on ', par_size(), ' rank(s)'
    write(output_unit, '(a,es12.5,a,f6.3,a,f6.3,a,f6.3)') '  t_end = ', config%t_end, &
        '  cfl = ', config%hydro%cfl, '  q_linear = ', config%hydro%q_linear, &
        '  q_quadratic = ', config%hydro%q_quadratic
    if (len_trim(restart) > 0) write(output_unit, '(a)') '  restart from '//trim(restart)
    flush(output_unit)
  end subroutine setup_echo

  !> The failure path's message (rank 0): what failed, where, when.
  subroutine failure_message(config, mesh, state, ctl)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(control_t), intent(in) :: ctl
    character(len=64) :: what
    real(rk) :: zone(4) !< block, density, sound speed, found (the owner's, summed)
    integer :: z, m
    character(len=:), allocatable :: text
    ! The zone that sets the step, from its owner (collective).
    zone = 0.0_rk
    if (ctl%fail == FAIL_DT) then
      do z = 1, mesh%nzone_owned
        if (mesh%zone_gid(z) /= ctl%fail_id) cycle
        zone = [real(mesh%zone_block(z), rk), state%zone_density(z), &
            state%zone_sound_speed(z), 1.0_rk]
      end do
      call par_sum_array(zone)
    end if
    if (par_rank() /= 0) return
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
    if (ctl%fail == FAIL_DT .and. zone(4) > 0.0_rk) then
      m = config%blocks(nint(zone(1)))%material
      text = '  zone '//to_text(ctl%fail_id)//': block '''// &
          trim(config%blocks(nint(zone(1)))%name)//''', material '''// &
          trim(config%materials(m)%name)//''''
      if (config%materials(m)%eos == EOS_MIE_GRUNEISEN) then
        text = text//', compression rho/rho0 = '//brief_text(zone(2) / &
            config%materials(m)%mg%rho0)//' (rho = '//brief_text(zone(2))//')'
      else
        text = text//', rho = '//brief_text(zone(2))//' (no reference density)'
      end if
      text = text//', sound speed '//brief_text(zone(3))//' '// &
          unit_of(config%units, 'velocity')
      write(error_unit, '(a)') text
    end if
    write(error_unit, '(a)') '  writing a final dump and stopping'
    flush(error_unit)
  end subroutine failure_message

  subroutine max_cycles_message(config, state)
    type(config_t), intent(in) :: config
    type(state_t), intent(in) :: state
    if (par_rank() == 0) write(error_unit, '(a,i0,a,es12.5,a)') &
        'impact3d: stopped at max_cycles = ', config%max_cycles, ' before t_end (t = ', &
        state%time, '); the last dump is a restart point'
  end subroutine max_cycles_message

  !> The contact audit asked for a stop (on_penetration = 'stop'; the audit
  !> printed why).
  subroutine audit_stop_message()
    if (par_rank() == 0) write(error_unit, '(a)') '  writing a final dump and stopping'
  end subroutine audit_stop_message

  !> The end by &control stop_block (rank 0): the block's kinetic energy fell
  !> below stop_kinetic_fraction of its initial value.
  subroutine kinetic_stop_message(config, state, kinetic)
    type(config_t), intent(in) :: config
    type(state_t), intent(in) :: state
    real(rk), intent(in) :: kinetic !< the block's kinetic energy now
    character(len=16) :: now, initial, t
    if (par_rank() /= 0) return
    write(now, '(es12.5)') kinetic
    write(initial, '(es12.5)') state%stop_kinetic_initial
    write(t, '(es12.5)') state%time
    write(output_unit, '(a,i0,a)') 'impact3d: stopping at cycle ', state%cycle, ', t = '// &
        trim(adjustl(t))//': the kinetic energy of block '''//trim(config%stop_block)// &
        ''' ('//trim(adjustl(now))//') fell below stop_kinetic_fraction = '// &
        fixed_text(config%stop_kinetic_fraction, 4)//' of its initial value ('// &
        trim(adjustl(initial))//')'
    flush(output_unit)
  end subroutine kinetic_stop_message

  !> A clean stop (rank 0): why, before the restart dump (done = .false.),
  !> and after it was written (done = .true.).
  subroutine stop_message(config, state, ctl, elapsed, done)
    type(config_t), intent(in) :: config
    type(state_t), intent(in) :: state
    type(control_t), intent(in) :: ctl
    real(rk), intent(in) :: elapsed !< seconds since the start of the run
    logical, intent(in) :: done
    if (par_rank() /= 0) return
    if (done) then
      write(output_unit, '(a,i0,a)') 'impact3d: stopped at cycle ', state%cycle, &
          ' with a restart dump, '//fixed_text(elapsed, 2)//' s after the start; exit code 3'
      return
    end if
    select case (ctl%stop)
    case (STOP_FILE)
      write(output_unit, '(a)') 'impact3d: stop file '''//trim(config%output%directory)// &
          '/'//trim(config%stop_file)//''' found: writing a restart dump and stopping '// &
          '(remove the file before restarting)'
    case (STOP_WALL)
      write(output_unit, '(a)') 'impact3d: close to the wall-time limit ('// &
          fixed_text(elapsed, 2)//' s of wall_limit = '// &
          fixed_text(config%wall_limit, 2)//' s used): writing a restart dump and stopping'
    case default
      write(output_unit, '(a)') 'impact3d: signal '//trim(signal_name(ctl%stop_signal))// &
          ' received: writing a restart dump and stopping'
    end select
    flush(output_unit)
  end subroutine stop_message

  !> The one timing report at the end of a run: each section of timers,
  !> largest over the ranks (a section within another indented under it), the
  !> rest of the time loop, the node halo line, and the closing line with
  !> rank 0's loop and dump seconds.
  subroutine timing_report(timers, cycles, loop_seconds)
    type(timers_t), intent(in) :: timers
    integer(i8), intent(in) :: cycles
    real(rk), intent(in) :: loop_seconds !< this rank's time loop, dumps included
    real(rk) :: t(timers%count), loop, top
    integer :: k
    call memory_report()
    do k = 1, timers%count
      t(k) = par_max(timers%timer(k)%total)
    end do
    loop = par_max(loop_seconds)
    if (par_rank() /= 0) return
    top = 0.0_rk
    do k = 1, timers%count
      if (timers%parent(k) == 0 .and. timers%names(k) /= 'set-up') top = top + t(k)
      if (timers%names(k) == 'halo') write(output_unit, '(a,f10.3,a)') &
          'impact3d: node halo exchange ', t(k), ' s (largest over the ranks)'
    end do
    write(output_unit, '(a)') 'impact3d: timing in s, largest over the ranks:'
    do k = 1, timers%count
      if (timers%parent(k) == 0) then
        write(output_unit, '(4x,a,f10.3)') timers%names(k), t(k)
      else
        write(output_unit, '(6x,a,f8.3)') timers%names(k), t(k)
      end if
    end do
    write(output_unit, '(4x,a,f10.3,a)') 'other           ', max(loop - top, 0.0_rk), &
        ' (the rest of the time loop)'
    write(output_unit, '(a,i0,a,f10.3,a,f8.3,a)') 'impact3d: done, ', cycles, ' cycles, ', &
        loop_seconds, ' s (', timers%total('dumps'), ' s of it in dumps)'
    flush(output_unit)
  end subroutine timing_report

  !> The halo traffic per cycle, largest over the ranks: bytes and messages
  !> each rank sent to refresh ghost nodes and ghost zones.
  subroutine halo_report(mesh, cycles)
    type(mesh_t), intent(in) :: mesh
    integer(i8), intent(in) :: cycles
    real(rk) :: bytes, messages
    bytes = par_max(real(mesh%node_halo%bytes_sent + mesh%zone_halo%bytes_sent, rk))
    messages = par_max(real(mesh%node_halo%messages_sent + mesh%zone_halo%messages_sent, rk))
    if (par_rank() /= 0 .or. par_size() == 1) return
    write(output_unit, '(a,f0.1,a,f0.1,a)') 'impact3d: halo exchange per cycle, largest rank: ', &
        bytes / real(max(cycles, 1_i8), rk) / 1.0e3_rk, ' kB in ', &
        messages / real(max(cycles, 1_i8), rk), ' messages'
  end subroutine halo_report

  !> The peak resident memory (VmHWM) of rank 0, the median rank and the
  !> largest rank, in MB: what a batch job must request per rank.
  subroutine memory_report()
    real(rk) :: mine(1)
    real(rk), allocatable :: all(:, :), sorted(:)
    integer :: n, largest
    n = par_size()
    allocate(all(1, n), sorted(n))
    mine(1) = peak_memory_mb()
    call par_allgather(mine, all)
    if (par_rank() /= 0) return
    sorted = all(1, :)
    call sort_values(sorted)
    largest = maxloc(all(1, :), dim=1)
    write(output_unit, '(a,f0.1,a,f0.1,a,f0.1,a,i0,a)') 'impact3d: peak memory per rank (VmHWM): rank 0 ', &
        all(1, 1), ' MB, median ', sorted((n + 1) / 2), ' MB, largest ', all(1, largest), &
        ' MB (rank ', largest - 1, ')'
  end subroutine memory_report

end module io_output
