!> The Lagrangian step: the predictor-corrector cycle of the staggered scheme
!> with the contact coupling and the strength update (docs/design.md, the
!> cycle). Above hydro and contact, below io and app: no deck, no output.
module solver_step
  use core_kinds, only: rk, i8
  use core_exact_sum, only: exact_sum_t, exact_value
  use core_timer, only: wall_time, timers_t
  use mesh_local, only: mesh_t
  use material_table, only: material_t
  use hydro_state, only: state_t, hydro_options_t, HOURGLASS_STIFFNESS
  use hydro_boundary, only: boundary_t, boundary_prescribed
  use hydro_driver, only: material_zones_t, hydro_zone_update, hydro_forces, &
      hydro_energy_update, hydro_velocity_update, hydro_strength_update, hydro_heat_flux
  use material_failure, only: failure_t, erosion_spec_t
  use hydro_erosion, only: erosion_step
  use contact_enforce, only: contact_t, contact_apply, contact_work_update, &
      contact_surface_refresh, side_context_t
  use contact_monitor, only: contact_audit_run, contact_step_end, contact_audit_due, &
      contact_depths, contact_refresh_offsets
  use parallel_env, only: par_sum_exact
  use solver_schedule, only: schedule_t
  implicit none
  private
  public :: solver_cycle, solver_lagrange_step, solver_audit, solver_contact_refresh

contains

  !> A cycle of dt (from plan%choose_step) with its bookkeeping: the step,
  !> the boundary and contact work summed over the ranks, the contact
  !> interfaces' step diagnostics, time landed on the dump time or t_end,
  !> cycle count, the stable step kept for the growth limit; then the contact
  !> audit when a global search ran or a dump ends the cycle. Sections 'step'
  !> (with 'halo' and 'contact' within) and 'audit' of timers. With failure
  !> or erosion the cycle ends with erosion_step (spall, the erosion decision,
  !> the lists); after an erosion anywhere the contact surfaces given by
  !> blocks follow the live zones (solver_contact_refresh).
  subroutine solver_cycle(opt, materials, mesh, state, mz, bc, ct, plan, dt, bad_half, bad, &
      timers, failures, erosion, sides)
    type(hydro_options_t), intent(in) :: opt
    type(material_t), intent(in) :: materials(:)
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(inout) :: state
    type(material_zones_t), intent(inout) :: mz
    type(boundary_t), intent(inout) :: bc
    type(contact_t), intent(inout) :: ct
    type(schedule_t), intent(inout) :: plan !< shortened when the contact cuts the step
    real(rk), intent(in) :: dt !< the planned step
    integer, intent(out) :: bad_half, bad !< local zones with bad volume (0 = none)
    type(timers_t), intent(inout) :: timers
    type(failure_t), intent(in) :: failures(:) !< per material
    type(erosion_spec_t), intent(in) :: erosion !< &erosion
    type(side_context_t), intent(in) :: sides !< blocks and closed sets (contact surfaces)
    type(exact_sum_t) :: work(2) !< boundary, contact work of the step
    integer :: eroded
    real(rk) :: step
    call timers%start('step')
    step = dt
    ct%landing = min(dt / max(plan%dt_stable, tiny(1.0_rk)), 1.0_rk)
    if (opt%single_stage) then
      call solver_single_step(opt, materials, mesh, state, mz, bc, dt, bad, work(1), timers)
      bad_half = 0
    else
      call solver_lagrange_step(opt, materials, mesh, state, mz, bc, ct, step, bad_half, bad, &
          work(1), work(2), timers, failures)
      ! A step the contact cut short lands on nothing: the next one does.
      if (step < dt) call plan%shorten()
    end if
    state%dt = step
    ! Exact sums: the works, and so the history, do not depend on the rank count.
    call par_sum_exact(work)
    state%boundary_work = state%boundary_work + exact_value(work(1))
    call contact_step_end(ct, exact_value(work(2)))
    eroded = 0
    if (allocated(state%zone_damage) .or. allocated(state%zone_alive)) call erosion_step(mesh, &
        state, mz, failures, erosion, opt, bad_half, bad, eroded)
    if (eroded > 0) call solver_contact_refresh(mesh, state, bc, ct, sides, timers)
    state%time = plan%land(state%time, step)
    state%cycle = state%cycle + 1
    state%dt_previous = plan%dt_stable
    call timers%stop('step')
    if (contact_audit_due(ct, plan%audit_due(state%cycle))) call solver_audit(ct, state, timers)
  end subroutine solver_cycle

  !> After an erosion (or a restart that finds eroded zones): the contact
  !> surfaces given by blocks rebuilt from the live zones (section
  !> 'contact'); nothing without an interface. The surfaces' sizes,
  !> sagittas and audit reach are taken on the positions at t = 0, as the
  !> set-up takes them: so they depend on the live zones only, and a
  !> restart, which rebuilds them from the dump's liveness, gets the same
  !> (positions of the last erosion would not be in the dump). Collective.
  subroutine solver_contact_refresh(mesh, state, bc, ct, sides, timers)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(boundary_t), intent(in) :: bc
    type(contact_t), intent(inout) :: ct
    type(side_context_t), intent(in) :: sides
    type(timers_t), intent(inout) :: timers
    integer(i8), allocatable :: gid(:)
    real(rk), allocatable :: depth(:, :)
    if (ct%npair == 0) return
    call timers%start('contact')
    call contact_depths(ct, state%node_position, gid, depth)
    call contact_surface_refresh(ct, mesh, state%node_position_initial, state%node_mass, &
        state%zone_alive > 0.0_rk, sides, boundary_prescribed(bc, size(state%node_mass)))
    call contact_refresh_offsets(ct, state%node_position, gid, depth)
    call timers%stop('contact')
  end subroutine solver_contact_refresh

  !> The contact audit at x^n of the state (section 'audit' of timers); its
  !> gaps stay in the contact for the dumps. Nothing without an interface.
  subroutine solver_audit(ct, state, timers)
    type(contact_t), intent(inout) :: ct
    type(state_t), intent(inout) :: state
    type(timers_t), intent(inout) :: timers
    call timers%start('audit')
    call contact_audit_run(ct, state%node_position, state%cycle, state%time)
    call timers%stop('audit')
    ct%audit_seconds = ct%audit_seconds + timers%last('audit')
  end subroutine solver_audit

  !> One predictor-corrector cycle from t^n to t^n+1: forces at t^n, contact
  !> on the half step, half-step velocities, geometry and EOS at t^n+1/2;
  !> forces at t^n+1/2, contact on the final update (its work), final
  !> velocities, positions, energies, deviatoric stress and zone state.
  subroutine solver_lagrange_step(opt, materials, mesh, state, mz, bc, ct, dt, bad_half, bad, &
      work, contact_work, timers, failures)
    type(hydro_options_t), intent(in) :: opt
    type(material_t), intent(in) :: materials(:)
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(inout) :: state
    type(material_zones_t), intent(in) :: mz
    type(boundary_t), intent(inout) :: bc
    type(contact_t), intent(inout) :: ct
    !> the cycle's step; the contact's impact limit may shorten it before
    !> anything uses it (contact_apply's predictor)
    real(rk), intent(inout) :: dt
    integer, intent(out) :: bad_half, bad
    type(exact_sum_t), intent(inout) :: work !< + boundary work of the step (local terms)
    type(exact_sum_t), intent(inout) :: contact_work !< + contact work of the step (local terms)
    type(timers_t), intent(inout) :: timers !< sections 'halo' and 'contact'
    type(failure_t), intent(in), optional :: failures(:) !< per material: damage models
    logical :: strength

    call save_step_start(mesh, state)

    strength = allocated(state%zone_stress)

    ! Predictor: forces at t^n, half-step velocities, geometry and EOS at t^n+1/2.
    if (strength) then
      call hydro_forces(mesh, state, opt, bc, state%node_position, &
          state%node_velocity, 0.0_rk, state%zone_stress)
    else
      call hydro_forces(mesh, state, opt, bc, state%node_position, &
          state%node_velocity, 0.0_rk)
    end if
    ! Contact acts on the predictor's half step too, as the rigid wall does:
    ! otherwise the half-step geometry interpenetrates freely and the contact
    ! pressure lags half a step (the mirror test shows it). (The contact
    ! entries do nothing when the deck has no interface.)
    call timers%start('contact')
    call contact_apply(ct, state%node_position_old, state%node_velocity_old, &
        state%node_force, 0.5_rk * dt, state%cycle + 1, .false., wall_time, dt)
    call timers%stop('contact')
    call hydro_velocity_update(mesh, state, bc, 0.5_rk * dt, state%node_velocity_half)
    call timers%start('halo')
    call mesh%node_halo%exchange(state%node_velocity_half)
    call timers%stop('halo')
    call advance_positions(mesh%nnode, state%node_position_old, state%node_velocity_half, &
        0.5_rk * dt, state%node_position)
    call hydro_energy_update(mesh, state, state%node_velocity_half, 0.5_rk * dt)
    call hydro_zone_update(mesh, state, materials, mz, opt, bc, &
        state%node_position, state%node_velocity_half, bad_half)
    if (strength) call hydro_strength_update(mesh, state, materials, mz, &
        state%node_velocity_half, 0.5_rk * dt, state%zone_stress, state%zone_stress_half, .false.)

    ! Corrector: forces at t^n+1/2, final velocities, positions and energies.
    if (strength) then
      call hydro_forces(mesh, state, opt, bc, state%node_position, &
          state%node_velocity_half, dt, state%zone_stress_half)
    else
      call hydro_forces(mesh, state, opt, bc, state%node_position, &
          state%node_velocity_half, dt)
    end if
    ! Contact on the final update, boundary conditions re-imposed after it.
    call timers%start('contact')
    call contact_apply(ct, state%node_position_old, state%node_velocity_old, &
        state%node_force, dt, state%cycle + 1, .true., wall_time)
    call timers%stop('contact')
    call hydro_velocity_update(mesh, state, bc, dt, state%node_velocity, work)
    call timers%start('contact')
    call contact_work_update(ct, state%node_velocity_old, state%node_velocity, dt, &
        contact_work)
    call timers%stop('contact')
    call timers%start('halo')
    call mesh%node_halo%exchange(state%node_velocity)
    call timers%stop('halo')
    call mean_velocities(mesh%nnode, state%node_velocity_old, state%node_velocity, &
        state%node_velocity_half)
    call advance_positions(mesh%nnode, state%node_position_old, state%node_velocity_half, dt, &
        state%node_position)
    call hydro_energy_update(mesh, state, state%node_velocity_half, dt)
    if (opt%heat_flux_linear > 0.0_rk .or. opt%heat_flux_quadratic > 0.0_rk) &
        call heat_flux_step(opt, mesh, state, mz, dt, timers)
    ! Deviatoric stress over the whole step: mid-step geometry, mean velocity.
    if (strength) then
      state%zone_stress_half = state%zone_stress
      call hydro_strength_update(mesh, state, materials, mz, &
          state%node_velocity_half, dt, state%zone_stress_half, state%zone_stress, .true., &
          failures)
    end if
    if (opt%hourglass == HOURGLASS_STIFFNESS) state%zone_hourglass = &
        state%zone_hourglass_new
    call hydro_zone_update(mesh, state, materials, mz, opt, bc, &
        state%node_position, state%node_velocity, bad)
  end subroutine solver_lagrange_step

  !> One cycle with one force evaluation (experimental; gas only: no contact,
  !> no strength): forces at t^n, v^n+1 = v^n + dt F^n / M, x^n+1 = x^n +
  !> dt v^n+1 (symplectic Euler), e^n+1 = e^n - dt F^n . (v^n + v^n+1)/2 / m
  !> (the kinetic energy change, so total energy is conserved exactly), then
  !> the zone state at t^n+1.
  subroutine solver_single_step(opt, materials, mesh, state, mz, bc, dt, bad, work, timers)
    type(hydro_options_t), intent(in) :: opt
    type(material_t), intent(in) :: materials(:)
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(inout) :: state
    type(material_zones_t), intent(in) :: mz
    type(boundary_t), intent(inout) :: bc
    real(rk), intent(in) :: dt
    integer, intent(out) :: bad
    type(exact_sum_t), intent(inout) :: work !< + boundary work of the step (local terms)
    type(timers_t), intent(inout) :: timers
    call save_step_start(mesh, state)
    call hydro_forces(mesh, state, opt, bc, state%node_position, state%node_velocity, dt)
    call hydro_velocity_update(mesh, state, bc, dt, state%node_velocity, work)
    call timers%start('halo')
    call mesh%node_halo%exchange(state%node_velocity)
    call timers%stop('halo')
    call advance_positions(mesh%nnode, state%node_position_old, state%node_velocity, dt, &
        state%node_position)
    call mean_velocities(mesh%nnode, state%node_velocity_old, state%node_velocity, &
        state%node_velocity_half)
    call hydro_energy_update(mesh, state, state%node_velocity_half, dt)
    if (opt%heat_flux_linear > 0.0_rk .or. opt%heat_flux_quadratic > 0.0_rk) &
        call heat_flux_step(opt, mesh, state, mz, dt, timers)
    if (opt%hourglass == HOURGLASS_STIFFNESS) state%zone_hourglass = state%zone_hourglass_new
    call hydro_zone_update(mesh, state, materials, mz, opt, bc, &
        state%node_position, state%node_velocity, bad)
  end subroutine solver_single_step

  !> x^n, v^n, e^n kept for the step (position, velocity and energy updates
  !> start from them).
  subroutine save_step_start(mesh, state)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(inout) :: state
    call copy_values(3 * mesh%nnode, state%node_position, state%node_position_old)
    call copy_values(3 * mesh%nnode, state%node_velocity, state%node_velocity_old)
    call copy_values(mesh%nzone, state%zone_energy, state%zone_energy_old)
  end subroutine save_step_start

  !> Noh's heat flux over the step on the owned zones, then the ghosts'
  !> energies refreshed (section 'halo').
  subroutine heat_flux_step(opt, mesh, state, mz, dt, timers)
    type(hydro_options_t), intent(in) :: opt
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(inout) :: state
    type(material_zones_t), intent(in) :: mz
    real(rk), intent(in) :: dt
    type(timers_t), intent(inout) :: timers
    call hydro_heat_flux(mesh, state, opt, mz, dt)
    call timers%start('halo')
    call mesh%zone_halo%exchange(state%zone_energy)
    call timers%stop('halo')
  end subroutine heat_flux_step

  !> to = from, n values (explicit shape: a plain copy loop).
  subroutine copy_values(n, from, to)
    integer, intent(in) :: n
    real(rk), intent(in) :: from(n)
    real(rk), intent(inout) :: to(n)
    to = from
  end subroutine copy_values

  !> x = x_old + step v of nodes 1..n.
  subroutine advance_positions(n, x_old, v, step, x)
    integer, intent(in) :: n
    real(rk), intent(in) :: x_old(3, n), v(3, n)
    real(rk), intent(in) :: step
    real(rk), intent(inout) :: x(3, n)
    x = x_old + step * v
  end subroutine advance_positions

  !> v_mean = (v_old + v) / 2 of nodes 1..n.
  subroutine mean_velocities(n, v_old, v, v_mean)
    integer, intent(in) :: n
    real(rk), intent(in) :: v_old(3, n), v(3, n)
    real(rk), intent(inout) :: v_mean(3, n)
    v_mean = 0.5_rk * (v_old + v)
  end subroutine mean_velocities

end module solver_step
