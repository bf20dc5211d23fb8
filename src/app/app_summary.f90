!> The model as set up, checked and described before any cycle:
!> * model_speed_check: the initial node speeds against the unit-mistake
!>   limit (core_unit_checks), unless &control allow_high_speed;
!> * model_summary: what --check and the start of every run print, for
!>   generated and imported parts alike: per material its parameters and
!>   their source; per block zones, volume, mass, momentum and kinetic
!>   energy; per face set faces and area; per interface its surfaces, their
!>   nodes, method and tolerance; per probe the node and zone it landed on
!>   and the distance from the point asked; totals.
!> Everything is computed from the distributed local mesh (each rank's owned
!> zones and nodes) and summed over the ranks (parallel_env), never from a
!> whole-mesh array. Block momentum and kinetic energy use the corner masses
!> m_z/8 of the block's zones (the lumping of the nodal masses), so that the
!> blocks add up to the totals of the nodal masses.
module app_summary
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  use core_text, only: to_text
  use core_unit_checks, only: speed_limit, speed_limit_text, speed_mistake, brief_text
  use core_units, only: unit_of
  use mesh_geometry, only: HEX_FACE_NODES, quad_vector_area
  use mesh_local, only: mesh_t
  use material_table, only: material_t, EOS_IDEAL_GAS, EOS_MIE_GRUNEISEN, STRENGTH_NONE, &
      STRENGTH_ELASTIC_PLASTIC, STRENGTH_STEINBERG_GUINAN, STRENGTH_JOHNSON_COOK, &
      material_library_source
  use hydro_state, only: state_t
  use contact_surface, only: set_names_of
  use contact_sides, only: side_context_t, side_is_blocks, blocks_of, block_faces
  use core_sort, only: sort_unique
  use hydro_boundary, only: BC_SYMMETRY, BC_WALL
  use io_deck, only: config_t
  use io_probe, only: probes_t
  use parallel_env, only: par_rank, par_sum_array, par_max
  implicit none
  private
  public :: model_speed_check, model_summary, material_lines

  character(len=*), parameter :: RF = '(es22.14)' !< full precision for the sums

contains

  !> The fastest owned node against the limit of the deck's units.
  subroutine model_speed_check(config, mesh, state, status)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(status_t), intent(inout) :: status
    real(rk) :: limit, fastest(5), speed
    integer :: n
    character(len=:), allocatable :: keys
    limit = speed_limit(config%units)
    if (limit <= 0.0_rk .or. config%allow_high_speed) return
    fastest = 0.0_rk
    do n = 1, mesh%nnode_owned
      speed = norm2(state%node_velocity(:, n))
      if (speed > fastest(1)) fastest = [speed, real(mesh%node_gid(n), rk), &
          state%node_position(:, n)]
    end do
    ! The fastest over the ranks (ties: the highest node id): its owner alone
    ! contributes the rest.
    speed = par_max(fastest(1))
    if (fastest(1) /= speed) fastest = 0.0_rk
    if (fastest(2) /= par_max(fastest(2))) fastest = 0.0_rk
    if (.not. (speed > limit)) return
    call par_sum_array(fastest(2:5))
    if (nint(fastest(2)) == 0) return
    keys = 'velocity'
    if (any(config%regions%radial_u0 /= 0.0_rk)) keys = 'radial_u0'
    call status%add('&region: '//keys//': the initial speed of node '// &
        to_text(nint(fastest(2)))//' at ('//brief_text(fastest(3))//', '// &
        brief_text(fastest(4))//', '//brief_text(fastest(5))//') is '//brief_text(speed)// &
        ', above '//speed_limit_text(config%units)//'; '//speed_mistake(config%units)// &
        ' (if it is meant: &control allow_high_speed = .true.)')
  end subroutine model_speed_check

  !> The parameters and source of a material, one line each (indented).
  function material_lines(mat, units) result(lines)
    type(material_t), intent(in) :: mat
    character(len=*), intent(in) :: units
    character(len=600), allocatable :: lines(:)
    character(len=:), allocatable :: text
    allocate(lines(0))
    select case (mat%eos)
    case (EOS_IDEAL_GAS)
      text = 'ideal gas: gamma = '//brief_text(mat%gamma)
    case (EOS_MIE_GRUNEISEN)
      text = 'Mie-Gruneisen: rho0 = '//brief_text(mat%mg%rho0)//' '// &
          unit_of(units, 'density')//', c0 = '//brief_text(mat%mg%c0)//' '// &
          unit_of(units, 'velocity')//', s1 = '//brief_text(mat%mg%s1)//', gamma0 = '// &
          brief_text(mat%mg%gamma0)//', b = '//brief_text(mat%mg%b)
      if (mat%mg%p_min > -huge(1.0_rk)) text = text//', p_min = '//brief_text(mat%mg%p_min)
    case default
      text = 'equation of state '//to_text(mat%eos)
    end select
    lines = [character(len=600) :: lines, '    '//text]
    select case (mat%strength)
    case (STRENGTH_NONE)
      text = 'strength: none'
    case (STRENGTH_ELASTIC_PLASTIC)
      text = 'strength: elastic-plastic: G = '//brief_text(mat%shear_modulus)//', Y0 = '// &
          brief_text(mat%yield_stress)//', H = '//brief_text(mat%hardening_modulus)
    case (STRENGTH_STEINBERG_GUINAN)
      text = 'strength: Steinberg-Guinan: G0 = '//brief_text(mat%sg%g0)//', Y0 = '// &
          brief_text(mat%sg%y0)//', Ymax = '//brief_text(mat%sg%ymax)//', beta = '// &
          brief_text(mat%sg%beta)//', n = '//brief_text(mat%sg%n)//', A = '// &
          brief_text(mat%sg%a)//', B = '//brief_text(mat%sg%b)//', Tm0 = '// &
          brief_text(mat%sg%tm0)//' K, cv = '//brief_text(mat%sg%cv)
    case (STRENGTH_JOHNSON_COOK)
      text = 'strength: Johnson-Cook: G = '//brief_text(mat%shear_modulus)//', A = '// &
          brief_text(mat%jc%a)//', B = '//brief_text(mat%jc%b)//', n = '// &
          brief_text(mat%jc%n)//', C = '//brief_text(mat%jc%c)//', m = '// &
          brief_text(mat%jc%m)//', Tr = '//brief_text(mat%jc%tr)//' K, Tm = '// &
          brief_text(mat%jc%tm)//' K, cv = '//brief_text(mat%jc%cv)
    case default
      text = 'strength model '//to_text(mat%strength)
    end select
    lines = [character(len=600) :: lines, '    '//text]
    if (len_trim(mat%library) > 0) then
      text = 'source: library '''//trim(mat%library)//''' ('// &
          material_library_source(trim(mat%library))//'); keys given in the deck override it'
    else
      text = 'source: the deck'
    end if
    lines = [character(len=600) :: lines, '    '//text]
  end function material_lines

  !> The summary, on every rank (collective); rank 0 gets the lines, the
  !> others an empty list.
  subroutine model_summary(config, mesh, state, probes, lines)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(probes_t), intent(in) :: probes
    character(len=600), allocatable, intent(out) :: lines(:)
    integer, parameter :: NB = 7 !< per block: zones, volume, mass, momentum(3), kinetic energy
    real(rk), allocatable :: sums(:, :), sets(:, :), nodes(:), probe_data(:, :), flat(:)
    real(rk) :: corner_mass, v(3)
    integer :: nblock, z, k, b, s, f, i, j, count_nodes
    logical, allocatable :: on_set(:)
    character(len=:), allocatable :: text, unit_l, unit_m, unit_v, unit_e
    character(len=64), allocatable :: surface_names(:)
    character(len=:), allocatable :: other
    type(side_context_t) :: sides

    allocate(lines(0))
    unit_l = unit_of(config%units, 'length')
    unit_m = unit_of(config%units, 'mass')
    unit_v = unit_of(config%units, 'velocity')
    unit_e = unit_of(config%units, 'energy')
    ! Blocks: owned zones, corner masses.
    nblock = size(config%blocks)
    allocate(sums(NB, nblock + 1))
    sums = 0.0_rk
    do z = 1, mesh%nzone_owned
      b = mesh%zone_block(z)
      corner_mass = 0.125_rk * state%zone_mass(z)
      sums(1, b) = sums(1, b) + 1.0_rk
      sums(2, b) = sums(2, b) + state%zone_volume(z)
      sums(3, b) = sums(3, b) + state%zone_mass(z)
      do k = 1, 8
        v = state%node_velocity(:, mesh%zone_node(k, z))
        sums(4:6, b) = sums(4:6, b) + corner_mass * v
        sums(7, b) = sums(7, b) + 0.5_rk * corner_mass * dot_product(v, v)
      end do
    end do
    flat = reshape(sums(:, 1:nblock), [NB * nblock])
    call par_sum_array(flat)
    sums(:, 1:nblock) = reshape(flat, [NB, nblock])
    sums(:, nblock + 1) = sum(sums(:, 1:nblock), dim=2)
    ! Face sets: faces of owned zones, area at the current positions.
    allocate(sets(2, mesh%nset))
    sets = 0.0_rk
    do s = 1, mesh%nset
      do f = mesh%set_start(s), mesh%set_start(s + 1) - 1
        z = mesh%set_zone(f)
        if (z > mesh%nzone_owned) cycle
        sets(1, s) = sets(1, s) + 1.0_rk
        sets(2, s) = sets(2, s) + norm2(quad_vector_area(state%node_position(:, &
            mesh%zone_node(HEX_FACE_NODES(:, mesh%set_face(f)), z))))
      end do
    end do
    if (mesh%nset > 0) call par_sum_array(sets(1, :))
    if (mesh%nset > 0) call par_sum_array(sets(2, :))
    ! Interfaces: owned nodes on each side's face sets; for a side of
    ! blocks, the distinct nodes of the blocks' exterior faces (on every rank).
    allocate(nodes(2 * size(config%contacts)), on_set(mesh%nnode))
    nodes = 0.0_rk
    sides%block_names = config%blocks(:)%name
    sides%closed_sets = pack(config%boundaries(:)%set, config%boundaries(:)%kind == BC_SYMMETRY &
        .or. config%boundaries(:)%kind == BC_WALL)
    do i = 1, size(config%contacts)
      do j = 1, 2
        if (j == 1) then
          surface_names = set_names_of(config%contacts(i)%surface_a)
          other = trim(config%contacts(i)%surface_b)
        else
          surface_names = set_names_of(config%contacts(i)%surface_b)
          other = trim(config%contacts(i)%surface_a)
        end if
        if (side_is_blocks(set_or_blocks(i, j))) then
          ! (collective: every rank counts, rank 0's count goes into the sum)
          count_nodes = block_side_nodes()
          if (par_rank() == 0) nodes(2 * (i - 1) + j) = real(count_nodes, rk)
          cycle
        end if
        on_set = .false.
        do s = 1, mesh%nset
          if (.not. any(surface_names == mesh%set_name(s))) cycle
          do f = mesh%set_start(s), mesh%set_start(s + 1) - 1
            on_set(mesh%zone_node(HEX_FACE_NODES(:, mesh%set_face(f)), mesh%set_zone(f))) = &
                .true.
          end do
        end do
        nodes(2 * (i - 1) + j) = real(count(on_set(1:mesh%nnode_owned)), rk)
      end do
    end do
    if (size(nodes) > 0) call par_sum_array(nodes)
    ! Probes: the distance of the node from the point asked, on the node's owner.
    allocate(probe_data(1, size(probes%p)))
    probe_data = 0.0_rk
    do i = 1, size(probes%p)
      if (probes%p(i)%node_local > 0 .and. config%probes(i)%at_point) probe_data(1, i) = &
          norm2(state%node_position(:, probes%p(i)%node_local) - config%probes(i)%point)
    end do
    if (size(probes%p) > 0) call par_sum_array(probe_data(1, :))
    if (par_rank() /= 0) return

    call add('model summary ('//trim(config%units)//'):')
    do i = 1, size(config%materials)
      call add('  material '''//trim(config%materials(i)%name)//''':')
      lines = [character(len=600) :: lines, material_lines(config%materials(i), config%units)]
    end do
    do b = 1, nblock + 1
      if (b <= nblock) then
        text = '  block '''//trim(config%blocks(b)%name)//''' (material '''// &
            trim(config%materials(config%blocks(b)%material)%name)//'''):'
      else
        text = '  totals:'
      end if
      call add(text//' zones '//to_text(nint(sums(1, b)))//', volume '//real_text(sums(2, b))// &
          ' '//unit_l//'^3, mass '//real_text(sums(3, b))//' '//unit_m// &
          ', momentum ('//real_text(sums(4, b))//', '//real_text(sums(5, b))//', '// &
          real_text(sums(6, b))//') '//unit_m//' '//unit_v//', kinetic energy '// &
          real_text(sums(7, b))//' '//unit_e)
    end do
    do s = 1, mesh%nset
      call add('  face set '''//trim(mesh%set_name(s))//''': faces '// &
          to_text(nint(sets(1, s)))//', area '//real_text(sets(2, s))//' '//unit_l//'^2')
    end do
    do i = 1, size(config%contacts)
      associate(c => config%contacts(i))
        text = 'automatic'
        if (c%penetration_tolerance > 0.0_rk) text = brief_text(c%penetration_tolerance)// &
            ' '//unit_l
        call add('  interface '//to_text(i)//': surface_a '''//trim(c%surface_a)//''' ('// &
            to_text(nint(nodes(2 * i - 1)))//' nodes), surface_b '''//trim(c%surface_b)// &
            ''' ('//to_text(nint(nodes(2 * i)))//' nodes), method '//trim(c%method)// &
            ', penetration tolerance '//text)
      end associate
    end do
    do i = 1, size(probes%p)
      associate(p => probes%p(i), spec => config%probes(i))
        if (spec%at_point) then
          call add('  probe '''//trim(spec%name)//''': node '//to_text(p%node_gid)// &
              ' at '//real_text(probe_data(1, i))//' '//unit_l// &
              ' from the point asked, zone '//to_text(p%zone_gid))
        else
          call add('  probe '''//trim(spec%name)//''': node '//to_text(p%node_gid)// &
              ' (given), zone '//to_text(p%zone_gid))
        end if
      end associate
    end do

  contains

    subroutine add(line)
      character(len=*), intent(in) :: line
      lines = [character(len=600) :: lines, line]
    end subroutine add

    function real_text(x) result(t)
      real(rk), intent(in) :: x
      character(len=:), allocatable :: t
      character(len=32) :: buffer
      write(buffer, RF) x
      t = trim(adjustl(buffer))
    end function real_text

    !> The surface list of side jj of interface ii.
    function set_or_blocks(ii, jj) result(list)
      integer, intent(in) :: ii, jj
      character(len=:), allocatable :: list
      if (jj == 1) then
        list = trim(config%contacts(ii)%surface_a)
      else
        list = trim(config%contacts(ii)%surface_b)
      end if
    end function set_or_blocks

    !> Distinct nodes of the exterior faces of side j of interface i's blocks.
    integer function block_side_nodes() result(n)
      type(status_t) :: ignored
      integer, allocatable :: blocks(:), facing(:)
      integer(i8), allocatable :: ids(:), unique_ids(:)
      integer(ik), allocatable :: face_nodes(:, :)
      logical, allocatable :: live(:)
      integer :: m
      character(len=:), allocatable :: this
      this = set_or_blocks(i, j)
      call blocks_of(this, sides, 'summary', blocks, ignored)
      allocate(facing(0))
      if (side_is_blocks(other) .and. other /= this) then
        call blocks_of(other, sides, 'summary', facing, ignored)
        facing = pack(facing, [(all(blocks /= facing(m)), m = 1, size(facing))])
      end if
      allocate(live(mesh%nzone))
      live = .true.
      call block_faces(mesh, live, blocks, facing, sides, ids, face_nodes)
      unique_ids = int(reshape(face_nodes, [size(face_nodes)]), i8)
      call sort_unique(unique_ids)
      n = size(unique_ids)
    end function block_side_nodes

  end subroutine model_summary

end module app_summary
