!> Set-up of a run: the restart's checks, mesh, partition, blocks,
!> boundaries, initial state, contact, the restart read.
module app_setup
  use core_kinds, only: rk, ik
  use core_status, only: status_t
  use core_timer, only: timers_t
  use mesh_geometry, only: hex_centroid
  use mesh_global, only: global_mesh_t, mesh_make_box, mesh_append, NAME_LEN
  use mesh_gmsh, only: mesh_read_gmsh
  use mesh_curved, only: mesh_make_rod, mesh_make_tube, mesh_make_shell_octant, &
      mesh_make_ball_octant, mesh_make_box_minus_ball
  use mesh_local, only: mesh_t, mesh_build_local
  use contact_surface, only: set_names_of
  use hydro_state, only: state_t, state_init, HOURGLASS_STIFFNESS
  use hydro_boundary, only: boundary_t, boundary_setup, boundary_constrain
  use hydro_initial, only: initial_apply
  use hydro_driver, only: material_zones_t, material_zones_build
  use contact_enforce, only: contact_t, contact_setup
  use contact_monitor, only: contact_initial
  use contact_state, only: initial_offsets_t
  use io_deck, only: config_t
  use io_dump, only: dump_read
  use app_provenance, only: restart_deck_check
  use material_table, only: STRENGTH_NONE
  use parallel_env, only: par_size, par_rank, par_bcast
  use parallel_partition, only: partition_zones
  implicit none
  private
  public :: setup_run, setup_mesh, setup_state, assign_blocks

contains

  !> Everything between the deck and the first cycle that input can make
  !> fail, in order: a restart file's existence and its stored deck against
  !> this one (before anything else), the mesh, initial contact overlaps (may
  !> move nodes: before the nodal masses), the state, the contact set-up, the
  !> restart read (section 'restart read' of timers). Problems go to status.
  subroutine setup_run(config, restart, force, mesh, bc, state, mz, ct, timers, status)
    type(config_t), intent(in) :: config
    character(len=*), intent(in) :: restart !< restart dump, '' for a new run
    logical, intent(in) :: force !< restart even if groups that must not change did
    type(mesh_t), intent(out) :: mesh
    type(boundary_t), intent(out) :: bc
    type(state_t), intent(out) :: state
    type(material_zones_t), intent(out) :: mz
    type(contact_t), intent(out) :: ct
    type(timers_t), intent(inout) :: timers
    type(status_t), intent(inout) :: status
    type(global_mesh_t) :: global
    type(initial_offsets_t), allocatable :: offsets(:)
    logical :: exists
    if (len_trim(restart) > 0) then
      exists = .false.
      if (par_rank() == 0) inquire(file=restart, exist=exists)
      call par_bcast(exists)
      if (.not. exists) call status%add('&control: restart: file '''//trim(restart)// &
          ''' does not exist')
      if (status%ok()) call restart_deck_check(restart, config, force, status)
    end if
    if (status%ok()) call setup_mesh(config, global, mesh, bc, status)
    if (.not. status%ok()) return
    if (size(config%contacts) > 0) call contact_initial(config%contacts, global, offsets, status)
    if (status%ok()) call setup_state(config, global, mesh, bc, state, mz, status)
    if (status%ok()) call contact_setup(config%contacts, global, mesh, state%node_mass, ct, &
        status, offsets)
    if (.not. status%ok()) return
    call global%free()
    if (len_trim(restart) > 0) then
      call timers%start('restart read')
      call dump_read(restart, mesh, state, status)
      call timers%stop('restart read')
    end if
  end subroutine setup_run

  !> Each zone not yet in a block belongs to the last block whose box holds
  !> its centroid.
  subroutine assign_blocks(config, global, status)
    type(config_t), intent(in) :: config
    type(global_mesh_t), intent(inout) :: global
    type(status_t), intent(inout) :: status
    integer :: z, b, missing
    real(rk) :: c(3)
    character(len=32) :: text
    missing = 0
    do z = 1, global%nzone
      c = hex_centroid(global%coordinates(:, global%connectivity(:, z)))
      if (global%zone_block(z) /= 0) cycle
      do b = 1, size(config%blocks)
        associate(box => config%blocks(b)%box)
          if (c(1) >= box(1) .and. c(1) <= box(2) .and. c(2) >= box(3) .and. &
              c(2) <= box(4) .and. c(3) >= box(5) .and. c(3) <= box(6)) global%zone_block(z) = b
        end associate
      end do
      if (global%zone_block(z) == 0) missing = missing + 1
    end do
    if (missing > 0) then
      write(text, '(i0)') missing
      call status%add('&block: box: '//trim(text)//' zones lie in no block''s box '// &
          '(every zone needs a block)')
    end if
  end subroutine assign_blocks

  !> Imported meshes: the 3D physical group of each zone names its &block.
  subroutine assign_blocks_by_name(config, group_names, global, status)
    type(config_t), intent(in) :: config
    character(len=*), intent(in) :: group_names(:)
    type(global_mesh_t), intent(inout) :: global
    type(status_t), intent(inout) :: status
    integer, allocatable :: map(:)
    integer :: g, b, z
    allocate(map(size(group_names)))
    map = 0
    do g = 1, size(group_names)
      do b = 1, size(config%blocks)
        if (config%blocks(b)%name == group_names(g)) map(g) = b
      end do
      if (map(g) == 0 .and. any(global%zone_block == g)) call status%add('&block: name: the '// &
          'mesh''s physical volume '''//trim(group_names(g))//''' has no &block of that name')
    end do
    do b = 1, size(config%blocks)
      if (.not. any(group_names == config%blocks(b)%name)) call status%add('&block: name: '''// &
          trim(config%blocks(b)%name)//''' is not a physical volume of the mesh file')
    end do
    if (.not. status%ok()) return
    do z = 1, global%nzone
      global%zone_block(z) = map(global%zone_block(z))
    end do
  end subroutine assign_blocks_by_name

  !> Build the global mesh (every &mesh part, appended in deck order), check
  !> blocks and boundaries, partition, localise.
  subroutine setup_mesh(config, global, mesh, bc, status)
    type(config_t), intent(in) :: config
    type(global_mesh_t), intent(inout) :: global
    type(mesh_t), intent(inout) :: mesh
    type(boundary_t), intent(inout) :: bc
    type(status_t), intent(inout) :: status
    integer(ik), allocatable :: part(:)
    character(len=NAME_LEN), allocatable :: group_names(:)
    type(global_mesh_t) :: piece
    integer :: k, n, b
    character(len=16) :: where

    call global%free()
    allocate(global%coordinates(3, 0), global%connectivity(8, 0), global%zone_block(0))
    do k = 1, size(config%parts)
      associate(spec => config%parts(k))
        where = '&mesh'
        if (size(config%parts) > 1) write(where, '(a,i0,a)') '&mesh(', k, ')'
        select case (spec%mesh_type)
        case ('rod')
          call mesh_make_rod(spec%rod, piece, status)
        case ('tube')
          call mesh_make_tube(spec%tube, piece, status)
        case ('shell')
          call mesh_make_shell_octant(spec%shell, piece, status)
        case ('ball')
          call mesh_make_ball_octant(spec%ball, piece, status)
        case ('box_minus_ball')
          call mesh_make_box_minus_ball(spec%box_minus_ball, piece, status)
        case ('gmsh')
          call mesh_read_gmsh(trim(spec%mesh_file), piece, group_names, status)
        case default
          call mesh_make_box(spec%box, piece, status)
        end select
        if (.not. status%ok()) return
        if (spec%rotation_angle /= 0.0_rk) call rotate(piece%coordinates, &
            spec%rotation_axis, spec%rotation_angle)
        do n = 1, piece%nnode
          piece%coordinates(:, n) = piece%coordinates(:, n) + spec%offset
        end do
        ! Blocks: the part's own block, else its physical volumes (Gmsh), else
        ! the block boxes (after the parts are joined).
        if (len_trim(spec%block) > 0) then
          b = 0
          do n = 1, size(config%blocks)
            if (config%blocks(n)%name == spec%block) b = n
          end do
          if (b == 0) then
            call status%add(trim(where)//': block: '''//trim(spec%block)// &
                ''' is not the name of a &block')
            return
          end if
          piece%zone_block = int(b, ik)
        else if (spec%mesh_type == 'gmsh') then
          call assign_blocks_by_name(config, group_names, piece, status)
          if (.not. status%ok()) return
        else
          piece%zone_block = 0
        end if
        call mesh_append(global, piece, trim(spec%name))
        call piece%free()
      end associate
    end do
    call assign_blocks(config, global, status)
    if (.not. status%ok()) return
    allocate(part(global%nzone))
    call partition_zones(global%nnode, global%connectivity, par_size(), part)
    call mesh_build_local(global, part, mesh)
    call boundary_setup(config%boundaries, global, mesh, bc, status)
    call check_contacts(config, global, status)
  end subroutine setup_mesh

  !> Rotate points about the origin by angle (degrees, right-handed) about
  !> axis (Rodrigues' formula).
  subroutine rotate(x, axis, angle)
    real(rk), intent(inout) :: x(:, :)
    real(rk), intent(in) :: axis(3), angle
    real(rk) :: k(3), c, s, p(3)
    integer :: n
    k = axis / norm2(axis)
    c = cos(angle * acos(-1.0_rk) / 180.0_rk)
    s = sin(angle * acos(-1.0_rk) / 180.0_rk)
    do n = 1, size(x, 2)
      p = x(:, n)
      x(:, n) = p * c + s * [k(2) * p(3) - k(3) * p(2), k(3) * p(1) - k(1) * p(3), &
          k(1) * p(2) - k(2) * p(1)] + k * dot_product(k, p) * (1.0_rk - c)
    end do
  end subroutine rotate

  !> &contact pairs: their surfaces must be face sets of the mesh, checked
  !> here with the other set-up problems before any work; contact_setup
  !> (src/contact) builds the interfaces afterwards.
  subroutine check_contacts(config, global, status)
    type(config_t), intent(in) :: config
    type(global_mesh_t), intent(in) :: global
    type(status_t), intent(inout) :: status
    integer :: k
    character(len=16) :: where
    do k = 1, size(config%contacts)
      write(where, '(a,i0,a)') '&contact(', k, ')'
      call check_list('surface_a', config%contacts(k)%surface_a)
      call check_list('surface_b', config%contacts(k)%surface_b)
    end do

  contains

    subroutine check_list(key, list)
      character(len=*), intent(in) :: key, list
      character(len=NAME_LEN), allocatable :: names(:)
      integer :: i
      names = set_names_of(list)
      if (size(names) == 0) call status%add(trim(where)//': '//key//': no face set named')
      do i = 1, size(names)
        if (global%find_set(names(i)) == 0) call status%add(trim(where)//': '//key//': '''// &
            trim(names(i))//''' is not a face set of the mesh')
      end do
    end subroutine check_list

  end subroutine check_contacts

  !> Allocate the state and apply the initial conditions (positions from the
  !> global mesh); nodal masses are the sums of corner masses m_z / 8.
  subroutine setup_state(config, global, mesh, bc, state, mz, status)
    type(config_t), intent(in) :: config
    type(global_mesh_t), intent(in) :: global
    type(mesh_t), intent(inout) :: mesh
    type(boundary_t), intent(in) :: bc
    type(state_t), intent(inout) :: state
    type(material_zones_t), intent(out) :: mz
    type(status_t), intent(inout) :: status
    integer, allocatable :: zone_material(:)
    integer :: n, z, j
    real(rk) :: m
    call state_init(state, mesh%nnode, mesh%nzone, config%hydro%hourglass == HOURGLASS_STIFFNESS, &
        any(config%materials%strength /= STRENGTH_NONE))
    do n = 1, mesh%nnode
      state%node_position(:, n) = global%coordinates(:, mesh%node_gid(n))
    end do
    allocate(zone_material(mesh%nzone))
    do z = 1, mesh%nzone
      zone_material(z) = config%blocks(mesh%zone_block(z))%material
    end do
    call material_zones_build(zone_material, size(config%materials), mz)
    call initial_apply(config%regions, config%materials, zone_material, mesh, state, status)
    if (.not. status%ok()) return
    do n = 1, mesh%nnode_owned
      m = 0.0_rk
      do j = mesh%corner_start(n), mesh%corner_start(n + 1) - 1
        m = m + 0.125_rk * state%zone_mass((mesh%corner_list(j) - 1) / 8 + 1)
      end do
      state%node_mass(n) = m
    end do
    ! Boundary velocities hold from t = 0 (a piston moves from the start).
    call boundary_constrain(bc, state%node_velocity, .true.)
    call mesh%node_halo%exchange(state%node_velocity)
  end subroutine setup_state

end module app_setup
