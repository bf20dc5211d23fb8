!> The Lagrangian step: the predictor-corrector cycle of the staggered scheme
!> with the contact coupling and the strength update (docs/design.md, the
!> cycle). Above hydro and contact, below io and app: no deck, no output.
module solver_step
  use core_kinds, only: rk
  use core_timer, only: wall_time, timer_t
  use mesh_local, only: mesh_t
  use material_table, only: material_t
  use hydro_state, only: state_t, hydro_options_t, HOURGLASS_STIFFNESS
  use hydro_boundary, only: boundary_t
  use hydro_driver, only: material_zones_t, hydro_zone_update, hydro_forces, &
      hydro_energy_update, hydro_velocity_update, hydro_strength_update
  use contact_enforce, only: contact_t, contact_apply, contact_work_update
  implicit none
  private
  public :: solver_lagrange_step

contains

  !> One predictor-corrector cycle from t^n to t^n+1: forces at t^n, contact
  !> on the half step, half-step velocities, geometry and EOS at t^n+1/2;
  !> forces at t^n+1/2, contact on the final update (its work), final
  !> velocities, positions, energies, deviatoric stress and zone state.
  subroutine solver_lagrange_step(opt, materials, mesh, state, mz, bc, ct, dt, bad_half, bad, &
      work, contact_work, halo)
    type(hydro_options_t), intent(in) :: opt
    type(material_t), intent(in) :: materials(:)
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
      call hydro_forces(mesh, state, opt, bc, state%node_position, &
          state%node_velocity, 0.0_rk, state%zone_stress)
    else
      call hydro_forces(mesh, state, opt, bc, state%node_position, &
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
      call hydro_strength_update(mesh, state, materials, mz, &
          state%node_velocity_half, dt, state%zone_stress_half, state%zone_stress, .true.)
    end if
    if (opt%hourglass == HOURGLASS_STIFFNESS) state%zone_hourglass = &
        state%zone_hourglass_new
    call hydro_zone_update(mesh, state, materials, mz, opt, bc, &
        state%node_position, state%node_velocity, bad)
  end subroutine solver_lagrange_step

end module solver_step
