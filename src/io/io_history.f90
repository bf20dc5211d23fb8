!> history.txt: one `# ` header line naming the whitespace-separated
!> columns, a row for cycle 0, then one row per history_every cycles (energy,
!> momentum, boundary and contact work, the energy balance, and per contact
!> interface its diagnostic columns `<name>_<quantity>`, then per material
!> `<material>_internal`, `_kinetic`, `_plastic_work`, `_hourglass`; with
!> erosion then `eroded_zones`, `eroded_zone_mass`, `eroded_internal`,
!> `eroded_node_mass`, `eroded_kinetic`). Rank 0 writes it. With erosion the
!> internal energy columns are those of the live zones; the energy balance
!> adds what erosion took out (eroded_internal + eroded_kinetic).
module io_history
  use core_kinds, only: rk, i8
  use mesh_local, only: mesh_t
  use hydro_state, only: state_t
  use core_exact_sum, only: exact_sum_t, exact_value, exact_add_all, exact_add_each, &
      exact_merge
  use contact_enforce, only: contact_t, CONTACT_DIAG_COUNT, CONTACT_DIAG_NAMES
  use parallel_env, only: par_rank, par_sum_exact
  use io_deck, only: config_t
  use io_rows, only: rows_restart
  implicit none
  private
  public :: history_open, history_write, history_sums, relative_error

  !> Per-material columns, in the order of history_sums' per_material.
  character(len=*), parameter :: MATERIAL_COLUMNS(4) = [character(len=12) :: 'internal', &
      'kinetic', 'plastic_work', 'hourglass']
  !> Erosion columns (erosion on only), in the order of history_sums' eroded.
  character(len=*), parameter :: EROSION_COLUMNS(5) = [character(len=16) :: 'eroded_zones', &
      'eroded_zone_mass', 'eroded_internal', 'eroded_node_mass', 'eroded_kinetic']

contains

  !> history.txt: a fresh file, or on restart the lines up to the restart cycle
  !> (streamed: linear in the file's length, rows of any width).
  subroutine history_open(config, state, restarted)
    type(config_t), intent(in) :: config
    type(state_t), intent(in) :: state
    logical, intent(in) :: restarted
    integer :: k, j
    character(len=:), allocatable :: header
    if (par_rank() /= 0) return
    header = '# cycle time dt internal_energy kinetic_energy boundary_work '// &
        'total_energy energy_error momentum_x momentum_y momentum_z contact_work'
    do k = 1, size(config%contacts)
      do j = 1, CONTACT_DIAG_COUNT
        header = header//' '//trim(config%contacts(k)%name)//'_'//trim(CONTACT_DIAG_NAMES(j))
      end do
    end do
    do k = 1, size(config%materials)
      do j = 1, size(MATERIAL_COLUMNS)
        header = header//' '//trim(config%materials(k)%name)//'_'//trim(MATERIAL_COLUMNS(j))
      end do
    end do
    if (allocated(state%zone_alive)) then
      do j = 1, size(EROSION_COLUMNS)
        header = header//' '//trim(EROSION_COLUMNS(j))
      end do
    end if
    call rows_restart(trim(config%output%directory)//'/history.txt', header, restarted, ' ', &
        state%cycle)
  end subroutine history_open

  subroutine history_write(config, mesh, state, ct)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(contact_t), intent(in) :: ct
    real(rk) :: sums(5), total, eroded(5)
    real(rk), allocatable :: per_material(:, :), flat(:)
    integer :: unit, k
    allocate(per_material(4, size(config%materials)))
    call history_sums(config, mesh, state, sums, per_material, eroded)
    flat = reshape(per_material, [size(per_material)])
    if (par_rank() /= 0) return
    total = sums(1) + sums(2)
    open(newunit=unit, file=trim(config%output%directory)//'/history.txt', status='old', &
        position='append', action='write')
    write(unit, '(i0,10(1x,es23.15e3))', advance='no') state%cycle, state%time, state%dt, &
        sums(1), sums(2), state%boundary_work, total, relative_error(total, state, ct%work, &
        eroded(3) + eroded(5)), sums(3:5)
    write(unit, '(1x,es23.15e3)', advance='no') ct%work
    do k = 1, ct%ndeck
      write(unit, '(*(1x,es23.15e3))', advance='no') ct%pairs(k)%diag
    end do
    write(unit, '(*(1x,es23.15e3))', advance='no') flat
    if (allocated(state%zone_alive)) write(unit, '(*(1x,es23.15e3))', advance='no') eroded
    write(unit, '(a)') ''
    close(unit)
  end subroutine history_write

  !> The history's global sums, exact (core_exact_sum) so that they are
  !> bitwise the same on any rank count: per_material(:, m) = internal,
  !> kinetic (each corner's eighth of the zone mass at its node's velocity),
  !> plastic work, hourglass work of the owned zones of material m (the
  !> terms of hydro_material_energies); sums = internal and kinetic energy
  !> (the exact sums of the materials' terms), momentum x, y, z (owned
  !> nodes). With erosion the internal energies are the live zones', and
  !> eroded = eroded zones (count), their mass and internal energy, the mass
  !> of the nodes that left and the kinetic energy they took (0 without
  !> erosion). Collective.
  subroutine history_sums(config, mesh, state, sums, per_material, eroded)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    real(rk), intent(out) :: sums(5)
    real(rk), intent(out) :: per_material(:, :) !< (4, nmaterial)
    real(rk), intent(out), optional :: eroded(5)
    type(exact_sum_t), allocatable :: acc(:)
    integer :: z, n, m, k, nm, nzo, nno
    real(rk) :: v2
    real(rk), allocatable :: term(:), speed2(:)
    integer, allocatable :: which(:)
    nm = size(config%materials)
    nzo = mesh%nzone_owned
    nno = mesh%nnode_owned
    allocate(acc(5 + 4 * nm + 5), term(max(nzo, nno)), which(nzo), speed2(mesh%nnode))
    associate(v => state%node_velocity, mass => state%node_mass)
      ! Per material: internal energy, kinetic energy (each corner's eighth
      ! of the zone mass at its node's velocity), plastic and hourglass work.
      do n = 1, mesh%nnode
        speed2(n) = v(1, n) * v(1, n) + v(2, n) * v(2, n) + v(3, n) * v(3, n)
      end do
      do z = 1, nzo
        which(z) = 5 + 4 * (config%blocks(mesh%zone_block(z))%material - 1)
        term(z) = state%zone_mass(z) * state%zone_energy(z)
      end do
      if (allocated(state%zone_alive)) then
        ! An eroded zone's internal energy goes to eroded_internal (the last
        ! five accumulators: count, zone mass, internal, node mass, kinetic).
        k = 5 + 4 * nm
        do z = 1, nzo
          if (state%zone_alive(z) > 0.0_rk) cycle
          call acc(k + 1)%add(1.0_rk)
          call acc(k + 2)%add(state%zone_mass(z))
          call acc(k + 3)%add(term(z))
          term(z) = 0.0_rk
        end do
        do k = 1, size(state%dead_nodes)
          n = state%dead_nodes(k)
          call acc(5 + 4 * nm + 4)%add(mass(n))
        end do
        call exact_add_all(acc(5 + 4 * nm + 5), state%node_eroded_kinetic(1:nno))
      end if
      call exact_add_each(acc, which + 1, term(1:nzo))
      do z = 1, nzo
        v2 = 0.0_rk
        do k = 1, 8
          v2 = v2 + speed2(mesh%zone_node(k, z))
        end do
        term(z) = 0.0625_rk * state%zone_mass(z) * v2
      end do
      call exact_add_each(acc, which + 2, term(1:nzo))
      if (allocated(state%zone_plastic_work)) &
          call exact_add_each(acc, which + 3, state%zone_plastic_work(1:nzo))
      if (allocated(state%zone_hourglass_work)) &
          call exact_add_each(acc, which + 4, state%zone_hourglass_work(1:nzo))
      ! The totals of internal and kinetic energy are the materials' (exact
      ! sums add exactly); momentum over the owned nodes.
      do m = 1, nm
        call exact_merge(acc(1), acc(5 + 4 * (m - 1) + 1))
        call exact_merge(acc(2), acc(5 + 4 * (m - 1) + 2))
      end do
      do k = 1, 3
        do n = 1, nno
          term(n) = mass(n) * v(k, n)
        end do
        call exact_add_all(acc(2 + k), term(1:nno))
      end do
    end associate
    call par_sum_exact(acc)
    do k = 1, 5
      sums(k) = exact_value(acc(k))
    end do
    do m = 1, nm
      do k = 1, 4
        per_material(k, m) = exact_value(acc(5 + 4 * (m - 1) + k))
      end do
    end do
    if (present(eroded)) then
      do k = 1, 5
        eroded(k) = exact_value(acc(5 + 4 * nm + k))
      end do
    end if
  end subroutine history_sums

  real(rk) function relative_error(total, state, contact_work, eroded)
    real(rk), intent(in) :: total
    type(state_t), intent(in) :: state
    real(rk), intent(in) :: contact_work !< work of the contact forces so far
    real(rk), intent(in), optional :: eroded !< energy erosion took out (internal + kinetic)
    real(rk) :: out
    out = 0.0_rk
    if (present(eroded)) out = eroded
    relative_error = (total + out - state%boundary_work - contact_work - &
        state%energy_initial) / &
        max(abs(state%energy_initial), tiny(1.0_rk))
  end function relative_error

end module io_history
